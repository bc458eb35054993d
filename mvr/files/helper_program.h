#pragma once
// The programs mvr starts as children (mvr-import, mvr-encode): named by an
// environment variable, else beside the running program.
#include <sys/types.h>

#include <string>
#include <vector>

namespace mvr {

// `env`'s value if set, else `name` beside /proc/self/exe. Throws
// mvr::Error "PATH: WHAT is done by NAME, which is not beside this program
// (or set ENV)" when neither is there.
std::string helperProgram(const char* name, const char* env, const std::string& path, const std::string& what);

// A child started with one standard stream on a pipe (its stdin, which we
// write, or its stdout, which we read) and its stderr on another.
struct HelperProcess {
  pid_t pid = -1;
  int stream = -1;  // our end of the child's stdin or stdout
  int errors = -1;  // our end of its stderr
};
enum class HelperPipe { Stdin, Stdout };
// Starts argv[0] with argv; throws mvr::Error "PATH: cannot start ..."
// with nothing left open when it cannot.
HelperProcess spawnHelper(const std::vector<std::string>& argv, HelperPipe pipe, const std::string& path);
// Waits for a child to end (through interruptions); its wait status.
int waitHelper(pid_t pid);

}  // namespace mvr
