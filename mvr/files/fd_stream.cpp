#include "mvr/files/fd_stream.h"

#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "mvr/error.h"

namespace mvr {
namespace {

constexpr size_t kBufferBytes = 1 << 16;

struct Address {
  enum class Kind { Stdio, File, Unix, Tcp } kind;
  std::string path, host, port;
};

Address parse(const std::string& e) {
  if (e == "-") return {Address::Kind::Stdio};
  if (e.rfind("unix:", 0) == 0) return {Address::Kind::Unix, e.substr(5)};
  if (e.rfind("tcp:", 0) == 0) {
    const std::string rest = e.substr(4);
    const auto colon = rest.rfind(':');
    if (colon == std::string::npos) fail(e, "expected tcp:HOST:PORT");
    return {Address::Kind::Tcp, "", rest.substr(0, colon), rest.substr(colon + 1)};
  }
  return {Address::Kind::File, e};
}

int unixSocket(const std::string& path, sockaddr_un& addr) {
  if (path.size() >= sizeof addr.sun_path) fail("unix:" + path, "socket path too long");
  std::memset(&addr, 0, sizeof addr);
  addr.sun_family = AF_UNIX;
  std::memcpy(addr.sun_path, path.c_str(), path.size());
  int fd = socket(AF_UNIX, SOCK_STREAM, 0);
  if (fd < 0) fail("unix:" + path, std::strerror(errno));
  return fd;
}

addrinfo* resolve(const Address& a, bool passive) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = passive ? AI_PASSIVE : 0;
  addrinfo* list = nullptr;
  const int rc = getaddrinfo(a.host.empty() ? nullptr : a.host.c_str(), a.port.c_str(), &hints, &list);
  if (rc != 0) fail("tcp:" + a.host + ":" + a.port, gai_strerror(rc));
  return list;
}

}  // namespace

FdStreamBuf::FdStreamBuf(int fd, bool owns) : fd_(fd), owns_(owns), out_(kBufferBytes), in_(kBufferBytes) {
  setp(out_.data(), out_.data() + out_.size());
  setg(in_.data(), in_.data(), in_.data());
}

FdStreamBuf::~FdStreamBuf() {
  flushOut();
  if (owns_) close(fd_);
}

bool FdStreamBuf::flushOut() {
  const char* p = pbase();
  while (p < pptr()) {
    const ssize_t n = write(fd_, p, size_t(pptr() - p));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      writeError_ = n < 0 ? errno : EIO;
      return false;
    }
    p += n;
  }
  setp(out_.data(), out_.data() + out_.size());
  return true;
}

FdStreamBuf::int_type FdStreamBuf::overflow(int_type c) {
  if (!flushOut()) return traits_type::eof();
  if (!traits_type::eq_int_type(c, traits_type::eof())) {
    *pptr() = traits_type::to_char_type(c);
    pbump(1);
  }
  return traits_type::not_eof(c);
}

int FdStreamBuf::sync() { return flushOut() ? 0 : -1; }

std::streamsize FdStreamBuf::xsputn(const char* s, std::streamsize n) {
  if (n > epptr() - pptr()) {  // large writes go straight through
    if (!flushOut()) return 0;
    std::streamsize done = 0;
    while (done < n) {
      const ssize_t w = write(fd_, s + done, size_t(n - done));
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) {
        writeError_ = w < 0 ? errno : EIO;
        return done;
      }
      done += w;
    }
    return done;
  }
  std::memcpy(pptr(), s, size_t(n));
  pbump(int(n));
  return n;
}

FdStreamBuf::int_type FdStreamBuf::underflow() {
  if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
  ssize_t n;
  do n = read(fd_, in_.data(), in_.size());
  while (n < 0 && errno == EINTR);
  if (n <= 0) return traits_type::eof();
  setg(in_.data(), in_.data(), in_.data() + n);
  return traits_type::to_int_type(*gptr());
}

std::streamsize FdStreamBuf::xsgetn(char* s, std::streamsize n) {
  std::streamsize done = 0;
  while (done < n) {
    if (gptr() == egptr() && traits_type::eq_int_type(underflow(), traits_type::eof())) break;
    const std::streamsize k = std::min<std::streamsize>(n - done, egptr() - gptr());
    std::memcpy(s + done, gptr(), size_t(k));
    gbump(int(k));
    done += k;
  }
  return done;
}

int openForWriting(const std::string& endpoint) {
  const Address a = parse(endpoint);
  switch (a.kind) {
    case Address::Kind::Stdio: return dup(STDOUT_FILENO);
    case Address::Kind::File: {
      int fd = open(a.path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (fd < 0) fail(a.path, std::strerror(errno));
      return fd;
    }
    case Address::Kind::Unix: {
      sockaddr_un addr;
      int fd = unixSocket(a.path, addr);
      if (connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
        const std::string why = std::strerror(errno);
        close(fd);
        fail(endpoint, "cannot connect: " + why);
      }
      return fd;
    }
    case Address::Kind::Tcp: {
      addrinfo* list = resolve(a, false);
      for (addrinfo* ai = list; ai; ai = ai->ai_next) {
        int fd = socket(ai->ai_family, ai->ai_socktype, ai->ai_protocol);
        if (fd >= 0 && connect(fd, ai->ai_addr, ai->ai_addrlen) == 0) {
          freeaddrinfo(list);
          return fd;
        }
        if (fd >= 0) close(fd);
      }
      freeaddrinfo(list);
      fail(endpoint, "cannot connect");
    }
  }
  fail(endpoint, "unknown endpoint");
}

int openForReading(const std::string& endpoint) {
  const Address a = parse(endpoint);
  int listener = -1;
  switch (a.kind) {
    case Address::Kind::Stdio: return dup(STDIN_FILENO);
    case Address::Kind::File: {
      int fd = open(a.path.c_str(), O_RDONLY);
      if (fd < 0) fail(a.path, std::strerror(errno));
      return fd;
    }
    case Address::Kind::Unix: {
      sockaddr_un addr;
      listener = unixSocket(a.path, addr);
      unlink(a.path.c_str());
      if (bind(listener, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 || listen(listener, 1) != 0) {
        close(listener);
        fail(endpoint, std::string("cannot listen: ") + std::strerror(errno));
      }
      break;
    }
    case Address::Kind::Tcp: {
      addrinfo* list = resolve(a, true);
      for (addrinfo* ai = list; ai && listener < 0; ai = ai->ai_next) {
        listener = socket(ai->ai_family, ai->ai_socktype, ai->ai_protocol);
        int one = 1;
        setsockopt(listener, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
        if (listener >= 0 && (bind(listener, ai->ai_addr, ai->ai_addrlen) != 0 || listen(listener, 1) != 0)) {
          close(listener);
          listener = -1;
        }
      }
      freeaddrinfo(list);
      if (listener < 0) fail(endpoint, "cannot listen");
      break;
    }
  }
  const int fd = accept(listener, nullptr, nullptr);
  close(listener);
  if (a.kind == Address::Kind::Unix) unlink(a.path.c_str());
  if (fd < 0) fail(endpoint, std::string("accept failed: ") + std::strerror(errno));
  return fd;
}

}  // namespace mvr
