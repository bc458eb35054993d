#include "mvr/files/helper_program.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "mvr/error.h"

extern char** environ;

namespace mvr {

std::string helperProgram(const char* name, const char* env, const std::string& path, const std::string& what) {
  if (const char* set = std::getenv(env); set && *set) return set;
  std::error_code ec;
  const std::filesystem::path helper = std::filesystem::read_symlink("/proc/self/exe", ec).parent_path() / name;
  if (ec || access(helper.c_str(), X_OK) != 0)
    fail(path, what + " by " + name + ", which is not beside this program (or set " + env + ")");
  return helper.string();
}

HelperProcess spawnHelper(const std::vector<std::string>& argv, HelperPipe pipe, const std::string& path) {
  const std::string name = std::filesystem::path(argv.at(0)).filename().string();
  int stream[2], err[2];
  if (pipe2(stream, O_CLOEXEC) != 0) fail(path, "cannot start " + name + " (pipe)");
  if (pipe2(err, O_CLOEXEC) != 0) {
    close(stream[0]), close(stream[1]);
    fail(path, "cannot start " + name + " (pipe)");
  }
  // The child's end of the stream: the read end of its stdin, the write end of its stdout.
  const bool in = pipe == HelperPipe::Stdin;
  const int childEnd = in ? stream[0] : stream[1], ourEnd = in ? stream[1] : stream[0];
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, childEnd, in ? STDIN_FILENO : STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, err[1], STDERR_FILENO);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  HelperProcess child;
  const int spawned = posix_spawn(&child.pid, argv[0].c_str(), &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(childEnd), close(err[1]);
  if (spawned != 0) {
    close(ourEnd), close(err[0]);
    fail(path, "cannot start " + argv[0] + ": " + std::strerror(spawned));
  }
  child.stream = ourEnd, child.errors = err[0];
  return child;
}

int waitHelper(pid_t pid) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

}  // namespace mvr
