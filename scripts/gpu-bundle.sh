#!/usr/bin/env bash
# The GPU check on a machine that has a Vulkan-capable GPU and driver but none of Strata's
# libraries (no Debian packages, no network): `make` packs the binaries, every shared library they
# need except glibc's own, the validation layer and a short excerpt of the redkitchen sample into
# one folder; `run`, on the GPU machine, unpacks it, lists the devices, runs the benchmarks
# (`strata-bench fuse` at 1, 2 and 5 cm, `track`, `esdf`) and then the chosen device tests,
# and writes the logs, the JSON reports and a summary under $OUT.
#
# Usage: scripts/gpu-bundle.sh make [BUILD_DIR]   (default build/; writes BUNDLE, default .gpu/)
#        scripts/gpu-bundle.sh run  [BUNDLE]      (default .gpu/; results in $OUT, default gpu-out/)
# Env (make): FRAMES (60) frames of the excerpt; DATA (../shared/data/redkitchen); TESTS (the
#             device test binaries to take, space separated); BUNDLE (.gpu).
# Env (run):  OUT; WORK (/tmp/strata-gpu, emptied); STRATA_DEVICE (index or name substring; by
#             default the NVIDIA device when one is listed); TEST_JOBS (4) test binaries at once;
#             TEST_TIMEOUT (150) seconds per test binary; BENCH_FRAMES (all of the excerpt)
#             frames for `track` and `esdf`; STEPS ("fuse track esdf tests") what runs after
#             `strata devices`; GTEST_FILTER (see below); BUNDLE_CXX=1 uses the bundled libstdc++
#             even where the machine's own would do.
# The Vulkan loader is not in the bundle: where `ldconfig -p` lists no libvulkan.so.1, `run`
# unpacks .gl/*.deb into / as scripts/gpu-check.sh does (Debian's libvulkan1 and the GL dispatch
# libraries the NVIDIA driver needs: `apt-get download libvulkan1 libegl1 libglvnd0 libopengl0
# libgl1 libglx0 libgles2` into .gl/). Results: run.log (everything), summary.txt, fuse.json,
# track.json, esdf.json, tests.log.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
NVIDIA_ICD=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
DEFAULT_TESTS="test_vk_runtime test_tsdf_fusion test_raycast test_esdf test_esdf_query test_track
test_track_redkitchen test_mapper"

usage() {
  sed -n '9,10p' "${BASH_SOURCE[0]}" | sed 's/^# //' >&2
  exit 2
}

# Libraries linked in but never called on the paths the check runs (GDAL, DICOM and OpenEXR behind
# OpenCV's imgcodecs; Open3D's VTK, asset, network and window dependencies): each is replaced by a
# stub of the same soname that defines the symbols its users import; a stub function that is called
# after all prints "gpu-bundle stub: SYMBOL called" (run greps for it) and returns 0. Without them
# the libraries weigh about 300 MiB, over what the device tool carries.
DEFAULT_STUBS="libgdal.so.* libgdcm*.so.* libOpenEXR-*.so.* libvtk*.so.* libassimp.so.*
libdraco.so.* libcurl.so.* libfilament*.so.* libGLEW.so.* libglfw.so.* libzmq.so.*"

# Copies into LIBDIR every shared library that FILEs load (transitively; the dependencies of a
# stubbed library are not followed), glibc's own excepted (the target machine's are used: a foreign
# ld.so breaks), stripped and under its soname; libstdc++ and libgcc_s go to LIBDIR-cxx (run uses
# them only where the machine's own are older). Stubs (STUBS patterns) are built with cc.
collect_libs() {
  local libdir="$1"
  shift
  STUBS="${STUBS-$DEFAULT_STUBS}" python3 - "$libdir" "$@" <<'EOF'
import fnmatch, os, re, subprocess, sys, tempfile

libdir, files = sys.argv[1], sys.argv[2:]
stub_patterns = os.environ["STUBS"].split()
glibc = re.compile(r"^(ld-linux.*|libc|libm|libmvec|libdl|libpthread|librt|libresolv|libutil|libanl"
                   r"|libnsl|libBrokenLocale|libnss_.*|libthread_db|libcrypt)\.so")

def run(*cmd):
    return subprocess.run(cmd, check=True, capture_output=True, text=True).stdout

def needed(path):
    return re.findall(r"\(NEEDED\)\s+Shared library: \[(.*?)\]", run("readelf", "-d", path))

def dynsyms(path):
    """(name, version or None, type, size, defined) of each dynamic symbol."""
    out = []
    for line in run("readelf", "--dyn-syms", "-W", path).splitlines():
        f = line.split()
        if len(f) < 8 or not f[0].endswith(":") or f[4] == "LOCAL":
            continue
        name = re.sub(r" \(\d+\)$", "", " ".join(f[7:]))
        m = re.match(r"([^@]+)@@?(.+)$", name)
        name, version = (m.group(1), m.group(2)) if m else (name, None)
        size = int(f[2], 0) if f[2].isdigit() or f[2].startswith("0x") else 0
        out.append((name, version, f[3], size, f[6] != "UND"))
    return out

cache = {}
for line in run("ldconfig", "-p").splitlines()[1:]:
    m = re.match(r"\s*(\S+) \((.*?)\) => (\S+)", line)
    if m and "x86-64" in m.group(2):
        cache.setdefault(m.group(1), m.group(3))

def is_stub(soname):
    return any(fnmatch.fnmatch(soname, p) for p in stub_patterns)

real, stubs, users = {}, {}, {}
todo = list(files)
while todo:
    path = todo.pop()
    for soname in needed(path):
        if glibc.match(soname):
            continue
        users.setdefault(soname, set()).add(path)
        if soname in real or soname in stubs:
            continue
        if soname not in cache:
            sys.exit(f"gpu-bundle: {soname} (needed by {path}) not found by ldconfig")
        resolved = os.path.realpath(cache[soname])
        if is_stub(soname):
            stubs[soname] = resolved
        else:
            real[soname] = resolved
            todo.append(resolved)

os.makedirs(libdir + "-cxx", exist_ok=True)
for soname, path in sorted(real.items()):
    dest = libdir + "-cxx" if re.match(r"lib(stdc\+\+|gcc_s)\.so", soname) else libdir
    run("strip", "--strip-unneeded", "-o", os.path.join(dest, soname), path)

# A stub defines what the bundle's own files import from it (users that are stubs do not count).
for soname, path in sorted(stubs.items()):
    provided = {(n, v): (t, size) for n, v, t, size, d in dynsyms(path) if d}
    wanted = {}
    for user in users[soname]:
        if user in stubs.values():
            continue
        for n, v, t, size, d in dynsyms(user):
            if d:
                continue
            for key in ((n, v), (n, None)):
                if key in provided:
                    wanted[key] = provided[key]
                    break
            else:
                # Unversioned reference to a versioned definition, or the other way round.
                for (pn, pv), info in provided.items():
                    if pn == n:
                        wanted[(pn, pv)] = info
                        break
    code = ["#include <stdio.h>",
            "static void called(const char* s) {",
            f'  fprintf(stderr, "gpu-bundle stub: %s called ({soname} is a stub)\\n", s);',
            "}"]
    versions = {}
    for i, ((n, v), (t, size)) in enumerate(sorted(wanted.items(), key=lambda kv: (kv[0][0], kv[0][1] or ""))):
        if v:
            versions.setdefault(v, []).append(n)
        label = n.replace("\\", "\\\\").replace('"', '\\"')
        if t in ("FUNC", "IFUNC", "NOTYPE"):
            code.append(f'long f{i}(void) __asm__("{label}");')
            code.append(f'long f{i}(void) {{ called("{label}"); return 0; }}')
        elif t == "TLS":
            code.append(f'__thread char o{i}[{max(size, 1)}] __asm__("{label}");')
        else:
            code.append(f'char o{i}[{max(size, 1)}] __asm__("{label}") __attribute__((aligned(64))) = {{1}};')
    with tempfile.TemporaryDirectory() as tmp:
        src = os.path.join(tmp, "stub.c")
        open(src, "w").write("\n".join(code) + "\n")
        link = ["-Wl,-soname," + soname]
        if versions:
            script = os.path.join(tmp, "versions.map")
            open(script, "w").write("".join(
                f"{v} {{ global: {' '.join(n + ';' for n in names)} }};\n" for v, names in versions.items()))
            link.append("-Wl,--version-script=" + script)
        run("cc", "-shared", "-fPIC", "-Os", "-s", "-o", os.path.join(libdir, soname), src, *link)
    print(f"gpu-bundle: stub {soname}: {len(wanted)} symbols", file=sys.stderr)
print(f"gpu-bundle: {len(real)} libraries, {len(stubs)} stubs", file=sys.stderr)
EOF
}

# Copies the first FRAMES frames of a TUM-layout folder (as the 7-Scenes sample is laid out: depth
# and rgb lists, groundtruth.txt, plus frame-N.pose.txt where present) and its calibration files.
copy_excerpt() {
  local src="$1" dst="$2" frames="$3"
  mkdir -p "$dst"
  find "$src" -maxdepth 1 -type f ! -name 'frame-*' -exec cp {} "$dst/" \;
  local list
  for list in depth.txt rgb.txt; do
    [ -f "$src/$list" ] || continue
    awk -v n="$frames" '/^#/ { print; next } NF >= 2 && kept < n { print; kept++ }' \
      "$src/$list" > "$dst/$list"
    awk '!/^#/ && NF >= 2 { print $2 }' "$dst/$list" | while read -r file; do
      mkdir -p "$dst/$(dirname "$file")"
      cp "$src/$file" "$dst/$file"
      case "$file" in
        *frame-*.depth.png) pose="${file%.depth.png}.pose.txt"
                            [ -f "$src/$pose" ] && cp "$src/$pose" "$dst/$pose" ;;
      esac
    done
  done
  if [ -f "$src/groundtruth.txt" ] && [ -f "$dst/depth.txt" ]; then
    # Poses up to 0.1 s past the last depth frame (the reader pairs within 20 ms).
    local last
    last="$(awk '!/^#/ && NF >= 2 { t = $1 } END { print t }' "$dst/depth.txt")"
    awk -v last="$last" '/^#/ || $1 <= last + 0.1' "$src/groundtruth.txt" > "$dst/groundtruth.txt"
  fi
}

make_bundle() {
  local build bundle frames data stage
  build="$(cd "${1:-$ROOT/build}" && pwd)"
  bundle="${BUNDLE:-$ROOT/.gpu}"
  frames="${FRAMES:-60}"
  data="${DATA:-$ROOT/../shared/data/redkitchen}"
  stage="$(mktemp -d)"
  trap 'rm -rf "$stage"' RETURN
  mkdir -p "$stage/bin" "$stage/lib" "$stage/layers" "$stage/data"

  local bins=("$build/bin/strata" "$build/bench/strata-bench") t
  for t in ${TESTS:-$DEFAULT_TESTS}; do
    if [ -x "$build/test/$t" ]; then bins+=("$build/test/$t"); else echo "gpu-bundle: no $build/test/$t, skipped" >&2; fi
  done
  local b
  for b in "${bins[@]}"; do
    [ -x "$b" ] || { echo "gpu-bundle: $b missing: build first (scripts/build.sh)" >&2; exit 2; }
    strip --strip-unneeded -o "$stage/bin/$(basename "$b")" "$b"
  done

  # The validation layer (Debian's vulkan-validationlayers), found through its manifest.
  local manifest layer_lib=""
  manifest="$(ls /usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json 2>/dev/null || true)"
  if [ -n "$manifest" ]; then
    layer_lib="$(ldconfig -p | awk '/libVkLayer_khronos_validation.so / { print $NF; exit }')"
  fi
  if [ -n "$layer_lib" ]; then
    cp "$manifest" "$stage/layers/"
    strip --strip-unneeded -o "$stage/lib/libVkLayer_khronos_validation.so" "$layer_lib"
  else
    echo "gpu-bundle: no validation layer here (vulkan-validationlayers): tests will run without it" >&2
  fi

  collect_libs "$stage/lib" "${bins[@]}" ${layer_lib:+"$layer_lib"}

  copy_excerpt "$data" "$stage/data/$(basename "$data")" "$frames"
  {
    echo "git_commit $(git -C "$ROOT" rev-parse --short HEAD)$(git -C "$ROOT" diff --quiet HEAD -- . 2>/dev/null || echo -dirty)"
    echo "build $build ($(awk -F= '/^CMAKE_BUILD_TYPE/ { print $2 }' "$build/CMakeCache.txt"))"
    echo "made $(date -u +%Y-%m-%dT%H:%M:%SZ) on $(. /etc/os-release && echo "$PRETTY_NAME")"
    echo "frames $frames of $data"
  } > "$stage/manifest.txt"

  rm -rf "$bundle"
  mkdir -p "$bundle"
  cp "$stage/manifest.txt" "$bundle/"
  tar -C "$stage" -cf - . | xz -T0 -6 > "$bundle/payload.tar.xz"
  echo "gpu-bundle: $bundle: $(du -sh "$bundle" | cut -f1) packed from $(du -sh "$stage" | cut -f1):" >&2
  (cd "$stage" && du -sh bin lib lib-cxx layers data) >&2
  local gl_bytes=0 total
  [ -d "$ROOT/.gl" ] && gl_bytes="$(du -sb "$ROOT/.gl" | cut -f1)"
  total=$(( $(du -sb "$bundle" | cut -f1) + gl_bytes ))
  echo "gpu-bundle: bundle + .gl = $(( total / 1048576 )) MiB (the device tool carries 64 MiB with the tree)" >&2
}

# --- run: on the GPU machine ------------------------------------------------------------------

# Runs one step under a time limit, logging its command line and exit status; never fails the
# script (the summary says what failed).
step() {
  local name="$1" limit="$2"
  shift 2
  echo "== $name: $*"
  local start rc=0
  start="$(date +%s.%N)"
  timeout --kill-after=10 "$limit" "$@" || rc=$?
  local secs
  secs="$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')"
  [ "$rc" = 124 ] && echo "== $name: TIMEOUT after ${limit} s" || echo "== $name: exit $rc, ${secs} s"
  echo "$name exit=$rc seconds=$secs" >> "$WORK/steps.txt"
  return 0
}

# One test binary under TEST_TIMEOUT; its log in $WORK/tests/NAME.log, a verdict line beside it.
run_test() {
  local t="$1" name start rc=0 secs verdict
  name="$(basename "$t")"
  start="$(date +%s)"
  timeout --kill-after=10 "${TEST_TIMEOUT:-150}" "$t" > "$WORK/tests/$name.log" 2>&1 || rc=$?
  secs=$(( $(date +%s) - start ))
  verdict=PASS
  [ "$rc" = 0 ] || verdict="FAIL(exit $rc)"
  [ "$rc" = 124 ] && verdict="TIMEOUT"
  echo "$name $verdict ${secs}s $(grep -E '^\[  (PASSED|FAILED|SKIPPED) ' "$WORK/tests/$name.log" | tr '\n' ' ')" \
    > "$WORK/tests/$name.verdict"
}

run_tests() {
  # Device tests, TEST_JOBS binaries at once, each log kept whole. (A bare `wait` would also wait
  # for the tee above, which never ends: the jobs are waited for by pid.)
  local t pids=()
  for t in "$WORK"/bin/test_*; do
    [ -x "$t" ] || continue
    while [ "$(jobs -rp | wc -l)" -ge "${TEST_JOBS:-4}" ]; do sleep 0.5; done
    run_test "$t" &
    pids+=("$!")
  done
  local pid
  for pid in "${pids[@]}"; do wait "$pid" || true; done
  : > "$OUT/tests.log"
  for t in "$WORK"/tests/*.log; do
    echo "######## $(basename "$t" .log)" >> "$OUT/tests.log"
    cat "$t" >> "$OUT/tests.log"
  done
  cat "$WORK"/tests/*.verdict > "$WORK/tests-summary.txt" 2>/dev/null || true
  grep -h -E '^\[  FAILED  \] [A-Za-z]' "$WORK"/tests/*.log | sort -u >> "$WORK/tests-summary.txt" || true
  echo "== tests"
  cat "$WORK/tests-summary.txt"
}

summarize() {
  local python
  python="$(command -v python3 || true)"
  {
    cat "$WORK/manifest.txt"
    echo "device_selected ${STRATA_DEVICE:-(default pick)}"
    echo "validation $VALIDATION"
    echo "GTEST_FILTER $GTEST_FILTER"
    [ -n "${NVIDIA_SMI_LINE:-}" ] && echo "nvidia-smi $NVIDIA_SMI_LINE"
    echo "-- steps"
    cat "$WORK/steps.txt"
    echo "-- tests (per binary: gtest's summary lines)"
    cat "$WORK/tests-summary.txt" 2>/dev/null || true
    echo "-- stub calls (count, message; expected: static constructors, GDALAllRegister)"
    cat "$OUT/run.log" "$WORK"/tests/*.log 2>/dev/null | grep -o 'gpu-bundle stub: .*' | sort | uniq -c || true
  } > "$OUT/summary.txt"
  [ -n "$python" ] || return 0
  "$python" - "$OUT" >> "$OUT/summary.txt" <<'EOF' || true
import json, os, sys
out = sys.argv[1]
def load(name):
    try:
        with open(os.path.join(out, name)) as f:
            return json.load(f)
    except Exception as e:
        print(f"-- {name}: unreadable ({e})")
        return None
def stat(d, key):
    v = (d or {}).get(key)
    if isinstance(v, dict):
        return f"{v.get('mean', float('nan')):.3f}/{v.get('median', float('nan')):.3f}"
    return "-" if v is None else str(v)
fuse = load("fuse.json")
if fuse:
    print("-- fuse (ms per frame, mean/median)")
    print("machine", json.dumps(fuse.get("machine")))
    print("streaming_ceiling", json.dumps(fuse.get("streaming_ceiling")))
    for r in fuse.get("results", []):
        d = r.get("device", {})
        print(f"voxel {r.get('voxel_size_m')} m:",
              " ".join(f"{k}={stat(d, k)}" for k in
                       ("upload_ms", "normals_ms", "allocate_ms", "integrate_ms", "device_total_ms", "wall_ms")),
              f"frames_per_s_wall={d.get('frames_per_s_wall')}",
              f"touched_blocks_per_frame={stat(d, 'touched_blocks_per_frame')}",
              f"peak_device_mib={d.get('peak_device_mib')}")
        print("   mesh", json.dumps(d.get("mesh")), "checks", json.dumps(d.get("checks")),
              "vs_ceiling", json.dumps(r.get("integrate_vs_ceiling")))
        print("   open3d", json.dumps(r.get("open3d")))
esdf = load("esdf.json")
if esdf:
    print("-- esdf (5 cm; device ms mean/median)")
    for r in esdf.get("results", []):
        inc, full = r.get("incremental_per_frame", {}), r.get("full_recomputation", {})
        print(f"{r.get('input')}: frames={r.get('frames')} blocks={r.get('blocks')}",
              f"fusion={stat(r, 'fusion_device_ms_per_frame')}",
              f"incremental={stat(inc, 'device_ms')} full={stat(full, 'device_ms')}",
              f"cpu_reference_full_ms={r.get('cpu_reference_full_ms')}",
              "vs_reference", json.dumps(r.get("device_vs_reference")))
track = load("track.json")
if track:
    print("-- track")
    print(json.dumps({k: v for k, v in track.items() if k != "machine"}, indent=1)[:4000])
EOF
}

run_bundle() {
  local bundle
  export PATH="$PATH:/usr/sbin:/sbin"  # ldconfig
  bundle="$(cd "${1:-$ROOT/.gpu}" && pwd)"
  OUT="${OUT:-$ROOT/gpu-out}"
  mkdir -p "$OUT"
  OUT="$(cd "$OUT" && pwd)"
  WORK="${WORK:-/tmp/strata-gpu}"
  rm -rf "$WORK"
  mkdir -p "$WORK/tmp" "$WORK/tests"
  exec > >(tee -a "$OUT/run.log") 2>&1
  echo "== gpu-bundle run: $(date -u +%Y-%m-%dT%H:%M:%SZ), $(uname -srm), $(nproc) cores"
  echo "$(ldd --version 2>&1 | head -1) (the bundle needs glibc >= 2.35)"
  if command -v xz > /dev/null; then
    xz -dc "$bundle/payload.tar.xz" | tar -C "$WORK" -xf -
  else  # no xz-utils: Python's lzma
    python3 -c 'import lzma, shutil, sys; shutil.copyfileobj(lzma.open(sys.argv[1]), sys.stdout.buffer)' \
      "$bundle/payload.tar.xz" | tar -C "$WORK" -xf -
  fi
  cat "$WORK/manifest.txt"
  : > "$WORK/steps.txt"

  # The Vulkan loader and the NVIDIA driver's manifest (as scripts/gpu-check.sh).
  if [[ "$(ldconfig -p 2>/dev/null || true)" != *libvulkan.so.1* ]]; then
    if compgen -G "$ROOT/.gl/*.deb" > /dev/null; then
      echo "== no libvulkan.so.1 registered: unpacking .gl/*.deb into /"
      for deb in "$ROOT"/.gl/*.deb; do dpkg -x "$deb" /; done
      ldconfig
    else
      echo "gpu-bundle: no Vulkan loader (libvulkan.so.1) and no .gl/*.deb to unpack" >&2
      exit 2
    fi
  fi
  if [ -z "${VK_DRIVER_FILES:-}" ] && [ -f "$NVIDIA_ICD" ]; then export VK_DRIVER_FILES="$NVIDIA_ICD"; fi
  echo "VK_DRIVER_FILES=${VK_DRIVER_FILES:-(loader default)}"
  NVIDIA_SMI_LINE=""
  if command -v nvidia-smi > /dev/null; then
    NVIDIA_SMI_LINE="$(nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv,noheader 2>&1 | head -1 || true)"
    echo "nvidia-smi: $NVIDIA_SMI_LINE"
  fi

  # The bundle's libraries; its libstdc++/libgcc_s only where the machine's own are missing or
  # older than the build needs (a newer one serves both Strata and the driver).
  export LD_LIBRARY_PATH="$WORK/lib"
  if [ "${BUNDLE_CXX:-0}" = 1 ] ||
     LD_LIBRARY_PATH="$WORK/lib" ldd "$WORK"/bin/* "$WORK"/lib/*.so* 2>&1 | grep -q 'not found'; then
    export LD_LIBRARY_PATH="$WORK/lib:$WORK/lib-cxx"
    echo "== using the bundled libstdc++/libgcc_s"
  fi
  if ldd "$WORK"/bin/* "$WORK"/lib/*.so* 2>&1 | grep 'not found' | sort -u; then
    echo "gpu-bundle: the libraries above are still missing; the steps that need them will fail"
  fi
  export VK_LAYER_PATH="$WORK/layers"
  unset STRATA_VALIDATION
  export STRATA_DATA_DIR="$WORK/data" STRATA_WORLDS_DIR="$ROOT/worlds"
  local data
  data="$(ls -d "$WORK"/data/*/ | head -1)"
  data="${data%/}"
  cd "$WORK/tmp"

  step devices 30 "$WORK/bin/strata" devices
  if [ -z "${STRATA_DEVICE:-}" ] && "$WORK/bin/strata" devices 2>/dev/null | grep -qi nvidia; then
    export STRATA_DEVICE=NVIDIA
  fi
  echo "STRATA_DEVICE=${STRATA_DEVICE:-(default pick)}"

  # Benchmarks first, on the idle machine, without validation.
  local steps=" ${STEPS:-fuse track esdf tests} "
  [[ "$steps" == *" fuse "* ]] && step fuse 120 "$WORK/bin/strata-bench" fuse --data "$data" --voxel-sizes 0.01,0.02,0.05 \
      --frames 0 --reference-frames 0 --out "$OUT/fuse.json" > /dev/null
  local nframes
  nframes="${BENCH_FRAMES:-$(awk '!/^#/ && NF >= 2' "$data/depth.txt" | wc -l)}"
  [[ "$steps" == *" track "* ]] && step track 120 "$WORK/bin/strata-bench" track --data "$data" --frames "$nframes" \
      --out "$OUT/track.json" > /dev/null
  [[ "$steps" == *" esdf "* ]] && step esdf 90 "$WORK/bin/strata-bench" esdf --data "$data" --frames "$nframes" \
      --out "$OUT/esdf.json" > /dev/null

  # Is the validation layer usable? A context made with it says "validation on".
  VALIDATION="off (layer not in the bundle)"
  if [ -f "$WORK/layers/VkLayer_khronos_validation.json" ] && [ -x "$WORK/bin/test_vk_runtime" ]; then
    if STRATA_VALIDATION=1 timeout 30 "$WORK/bin/test_vk_runtime" \
         --gtest_filter=VkRuntime.CreatesContextWithSaneLimits > "$WORK/validation-probe.log" 2>&1 &&
       grep -q 'validation on' "$WORK/validation-probe.log"; then
      VALIDATION="on (VK_LAYER_KHRONOS_validation from the bundle, synchronization validation)"
      export STRATA_VALIDATION=1
    else
      VALIDATION="off: the bundled layer did not load (see run.log)"
      cat "$WORK/validation-probe.log"
    fi
  fi
  # VkRuntime.ValidationErrorsAreCounted records a dispatch with no pipeline bound on purpose; the
  # layer counts the error and passes the call on, and on NVIDIA's driver 580.159 the process then
  # dies (SIGSEGV), taking the binary's remaining tests with it. Left out here (CI runs it on
  # lavapipe).
  export GTEST_FILTER="${GTEST_FILTER:--VkRuntime.ValidationErrorsAreCounted}"
  echo "GTEST_FILTER=$GTEST_FILTER"
  echo "validation: $VALIDATION"

  [[ "$steps" == *" tests "* ]] && run_tests

  summarize
  echo "== summary ($OUT/summary.txt)"
  cat "$OUT/summary.txt"
}

case "${1:-}" in
  make) shift; make_bundle "$@" ;;
  run) shift; run_bundle "$@" ;;
  *) usage ;;
esac
