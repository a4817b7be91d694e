#pragma once
// Errors: every failure that ends an operation throws strata::Error with a message that names what
// failed and, where there is one, what to install or change.
// NOTE: exceptions rather than Result<T> so an error can never be silently ignored by a caller that
// forgot to check; the CLI turns them into a message and a non-zero exit.
#include <stdexcept>
#include <string>

namespace strata {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

/// Bad input data (files, images, poses, intrinsics, messages).
class InputError : public Error {
 public:
  explicit InputError(const std::string& what) : Error(what) {}
};

/// A device-side failure (Vulkan call, allocation, device loss).
class DeviceError : public Error {
 public:
  explicit DeviceError(const std::string& what) : Error(what) {}
};

}  // namespace strata
