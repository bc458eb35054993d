#pragma once
// User-facing errors: one line naming the input and the problem. Thrown
// anywhere, caught once in apps/ where they become stderr + non-zero exit.
#include <stdexcept>
#include <string>

namespace mvr {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// "where: what" -- where is a file name, a JSON path or a subsystem name.
[[noreturn]] inline void fail(const std::string& where, const std::string& what) {
  throw Error(where + ": " + what);
}

}  // namespace mvr
