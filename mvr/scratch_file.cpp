#include "mvr/scratch_file.h"

#include <fcntl.h>
#include <sys/uio.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <system_error>
#include <vector>

#include "mvr/error.h"

namespace mvr {

ScratchFile::ScratchFile(const std::string& dir) : dir_(dir) {
#ifdef O_TMPFILE
  fd_ = ::open(dir.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
#endif
  if (fd_ < 0) {  // file systems without O_TMPFILE: a unique name, unlinked at once
    std::string name = dir + "/.mvr_scratch_XXXXXX";
    fd_ = ::mkostemp(name.data(), O_CLOEXEC);
    if (fd_ < 0) failWith("cannot create a scratch file", errno);
    ::unlink(name.c_str());
  }
}

ScratchFile::~ScratchFile() {
  if (fd_ >= 0) ::close(fd_);
}

void ScratchFile::failWith(const char* what, int error) const {
  // generic_category: strerror is not thread-safe
  fail(dir_, std::string(what) + ": " + std::generic_category().message(error));
}

void ScratchFile::write(uint64_t offset, std::span<const std::byte> bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::pwrite(fd_, bytes.data(), bytes.size(), off_t(offset));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) failWith("cannot write the scratch file", n < 0 ? errno : ENOSPC);
    bytes = bytes.subspan(size_t(n));
    offset += uint64_t(n);
  }
}

void ScratchFile::read(uint64_t offset, std::span<const std::span<std::byte>> pieces) {
  std::vector<iovec> io;
  io.reserve(pieces.size());
  for (const auto& p : pieces)
    if (!p.empty()) io.push_back({p.data(), p.size()});
  size_t first = 0;  // a short read leaves the rest of the pieces to a next call
  while (first < io.size()) {
    const int count = int(std::min(io.size() - first, size_t(IOV_MAX)));
    const ssize_t n = ::preadv(fd_, io.data() + first, count, off_t(offset));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) failWith("cannot read the scratch file", errno);
    if (n == 0) failWith("cannot read the scratch file", EIO);  // past what was written
    offset += uint64_t(n);
    for (size_t left = size_t(n); left > 0;) {
      if (left >= io[first].iov_len) {
        left -= io[first].iov_len;
        ++first;
      } else {
        io[first].iov_base = static_cast<std::byte*>(io[first].iov_base) + left;
        io[first].iov_len -= left;
        left = 0;
      }
    }
  }
}

}  // namespace mvr
