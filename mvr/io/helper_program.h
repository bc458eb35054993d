#pragma once
// The programs mvr starts as children (mvr-import, mvr-encode): named by an
// environment variable, else beside the running program.
#include <string>

namespace mvr {

// `env`'s value if set, else `name` beside /proc/self/exe. Throws
// mvr::Error "PATH: WHAT is done by NAME, which is not beside this program
// (or set ENV)" when neither is there.
std::string helperProgram(const char* name, const char* env, const std::string& path, const std::string& what);

}  // namespace mvr
