#include "mvr/files/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <string>
#include <system_error>

#include "mvr/error.h"

namespace mvr {
namespace {

// Writes all of bytes to fd; errno is left set on failure.
bool writeAll(int fd, std::span<const std::byte> bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = EIO;
      return false;
    }
    bytes = bytes.subspan(size_t(n));
  }
  return true;
}

std::string partOf(const std::string& path) { return path + ".part"; }

[[noreturn]] void failWriting(const std::string& path, int error) {
  ::unlink(partOf(path).c_str());
  fail(path, "cannot write: " + std::generic_category().message(error));  // thread-safe, unlike strerror
}

// bytes into PATH.part, created or appended to.
void writePart(const std::string& path, std::span<const std::byte> bytes, bool append) {
  // Past a file-size limit the kernel would kill the process (SIGXFSZ)
  // before write() could report EFBIG; as an error it is one line.
  static const bool ignoreSizeSignal = [] { return std::signal(SIGXFSZ, SIG_IGN) != SIG_ERR; }();
  (void)ignoreSizeSignal;
  const int fd = ::open(partOf(path).c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | (append ? O_APPEND : O_TRUNC), 0666);
  if (fd < 0) failWriting(path, errno);
  int error = writeAll(fd, bytes) ? 0 : errno;
  if (::close(fd) != 0 && error == 0) error = errno;  // NFS and quotas report at close
  if (error != 0) failWriting(path, error);
}

void renamePart(const std::string& path) {
  if (std::rename(partOf(path).c_str(), path.c_str()) != 0) failWriting(path, errno);
}

}  // namespace

void writeFileAtomically(const std::string& path, std::span<const std::byte> bytes) {
  writePart(path, bytes, false);
  renamePart(path);
}

void appendToPart(const std::string& path, std::span<const std::byte> bytes, bool first) {
  writePart(path, bytes, !first);
}

void finishPart(const std::string& path, std::span<const std::byte> last) {
  writePart(path, last, true);
  renamePart(path);
}

void removePart(const std::string& path) { ::unlink(partOf(path).c_str()); }

std::string partName(const std::string& path) { return partOf(path); }

void commitPart(const std::string& path) { renamePart(path); }

}  // namespace mvr
