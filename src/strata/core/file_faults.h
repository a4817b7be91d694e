#pragma once
// Injected file-system failures, FOR TESTS ONLY: lets a test make one step of writeFileAtomically
// (core/atomic_file.h) fail with a chosen errno, as a full disk (ENOSPC), a read-only folder
// (EROFS, EACCES) or a failing device (EIO) would, on machines where a test cannot mount a small
// or read-only file system. The failure takes the same path as a real one.
// Off by default; production code never arms it. Zero cost when unarmed: one relaxed atomic load
// per step. docs/faults.md lists the faults and the tests that use them.
// Thread safety: every function is thread safe.
namespace strata {

/// The system calls of writeFileAtomically a fault can replace.
enum class FileStep { kOpen, kWrite, kFsync, kRename };

class FileFaultInjection {
 public:
  /// The next call of `step` (in any thread) fails with errno `error_number` (> 0), once; an
  /// armed fault of another step stays armed.
  static void arm(FileStep step, int error_number);
  /// Disarms every step.
  static void disarm();
  /// Called by the file writer before `step`: the errno to fail with (consuming it), or 0.
  static int take(FileStep step);
};

/// Arms one fault for the lifetime of the object (disarms all on destruction).
class ScopedFileFault {
 public:
  ScopedFileFault(FileStep step, int error_number) { FileFaultInjection::arm(step, error_number); }
  ~ScopedFileFault() { FileFaultInjection::disarm(); }
  ScopedFileFault(const ScopedFileFault&) = delete;
  ScopedFileFault& operator=(const ScopedFileFault&) = delete;
};

}  // namespace strata
