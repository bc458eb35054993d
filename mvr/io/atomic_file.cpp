#include "mvr/io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
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

}  // namespace

void writeFileAtomically(const std::string& path, std::span<const std::byte> bytes) {
  // Past a file-size limit the kernel would kill the process (SIGXFSZ)
  // before write() could report EFBIG; as an error it is one line.
  static const bool ignoreSizeSignal = [] { return std::signal(SIGXFSZ, SIG_IGN) != SIG_ERR; }();
  (void)ignoreSizeSignal;
  const std::string tmp = path + ".part";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) fail(path, "cannot write: " + std::generic_category().message(errno));
  int error = writeAll(fd, bytes) ? 0 : errno;
  if (::close(fd) != 0 && error == 0) error = errno;  // NFS and quotas report at close
  if (error == 0 && std::rename(tmp.c_str(), path.c_str()) != 0) error = errno;
  if (error != 0) {
    ::unlink(tmp.c_str());
    fail(path, "cannot write: " + std::generic_category().message(error));  // thread-safe, unlike strerror
  }
}

}  // namespace mvr
