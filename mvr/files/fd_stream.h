#pragma once
// std::iostream over a file descriptor (pipe, socket, file), and the
// endpoints the EPI stream travels over: "-" (stdin/stdout), a file path,
// "unix:PATH" or "tcp:HOST:PORT". Consumers listen, producers connect.
#include <streambuf>
#include <string>
#include <vector>

namespace mvr {

class FdStreamBuf final : public std::streambuf {
 public:
  explicit FdStreamBuf(int fd, bool owns = true);
  ~FdStreamBuf() override;
  FdStreamBuf(const FdStreamBuf&) = delete;
  FdStreamBuf& operator=(const FdStreamBuf&) = delete;
  // errno of the write that failed, 0 while none has.
  int writeError() const { return writeError_; }

 protected:
  int_type overflow(int_type c) override;
  int sync() override;
  std::streamsize xsputn(const char* s, std::streamsize n) override;
  int_type underflow() override;
  std::streamsize xsgetn(char* s, std::streamsize n) override;

 private:
  bool flushOut();
  int fd_;
  bool owns_;
  int writeError_ = 0;
  std::vector<char> out_, in_;
};

// Opens an endpoint for writing (producer): stdout, a file (truncated),
// or a connection to a listening consumer. Throws mvr::Error naming it.
int openForWriting(const std::string& endpoint);
// Opens an endpoint for reading (consumer): stdin, a file, or a listening
// socket that accepts one producer.
int openForReading(const std::string& endpoint);

}  // namespace mvr
