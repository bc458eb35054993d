#include "mvr/io/helper_program.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "mvr/error.h"

namespace mvr {

std::string helperProgram(const char* name, const char* env, const std::string& path, const std::string& what) {
  if (const char* set = std::getenv(env); set && *set) return set;
  std::error_code ec;
  const std::filesystem::path helper = std::filesystem::read_symlink("/proc/self/exe", ec).parent_path() / name;
  if (ec || access(helper.c_str(), X_OK) != 0)
    fail(path, what + " by " + name + ", which is not beside this program (or set " + env + ")");
  return helper.string();
}

}  // namespace mvr
