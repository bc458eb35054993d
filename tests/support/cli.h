#pragma once
// Running the built programs from tests, as a user would.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace mvr::test {

struct CliResult {
  int status;
  std::string err;
};

// Runs a shell command line; returns its exit status and stderr.
inline CliResult shell(const std::string& commandLine) {
  // Errors only: a run slowed past a second (sanitizers, a loaded machine)
  // would add progress lines.
  setenv("MVR_PROGRESS", "0", 1);
  // ctest runs tests in parallel processes: one stderr file per process.
  const auto errFile = std::filesystem::temp_directory_path() /
                       ("mvr_cli_stderr_" + std::to_string(getpid()) + ".txt");
  const std::string cmd = "(" + commandLine + ") 2>" + errFile.string();
  const int rc = std::system(cmd.c_str());
  std::stringstream ss;
  ss << std::ifstream(errFile).rdbuf();
  return {WEXITSTATUS(rc), ss.str()};
}

// A run that exited 0, or a failure that shows the run's exit status and
// stderr: a sanitizer's report, or the LeakSanitizer tracer's crash at exit
// that scripts/sanitize looks for in the log to rerun without leak checks.
inline ::testing::AssertionResult succeeded(const CliResult& r) {
  if (r.status == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "exit status " << r.status << ", stderr:\n" << r.err;
}
// A run that exited `status` (an error path's 1), or a failure that shows
// what it exited with and its stderr.
inline ::testing::AssertionResult exitedWith(const CliResult& r, int status) {
  if (r.status == status) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "exit status " << r.status << " (expected " << status << "), stderr:\n"
                                       << r.err;
}
// A run that failed (any non-zero status), or a failure that shows its
// stderr: what the program said as it went through.
inline ::testing::AssertionResult failed(const CliResult& r) {
  if (r.status != 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "exit status 0 (expected a failure), stderr:\n" << r.err;
}

// The programs under test: MVR_TEST_MVR and MVR_TEST_CONSUME from the
// environment (packed copies on another machine), else the build's.
inline std::string mvrBinary() {
  const char* path = std::getenv("MVR_TEST_MVR");
  return path ? path : MVR_BINARY;
}
inline std::string consumeBinary() {
  const char* path = std::getenv("MVR_TEST_CONSUME");
  return path ? path : MVR_CONSUME;
}

inline CliResult runMvr(const std::string& args) {
  return shell(mvrBinary() + " " + args + " >/dev/null");
}

inline std::filesystem::path freshDir(const std::string& name) {
  auto d = std::filesystem::temp_directory_path() / ("mvr_test_" + name + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(d);
  return d;
}

}  // namespace mvr::test
