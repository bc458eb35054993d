#pragma once
// A file that holds what does not fit in memory (a row's EPI volume on its
// way to view order), created unnamed in a folder the caller chooses: the
// output folder, not /tmp, which is often memory itself. The file has no
// name from the start (O_TMPFILE, or a unique name removed at once), so a
// crash or a kill leaves nothing behind. Every read and write is checked
// and a failure names the folder and the system's reason ("No space left
// on device").
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace mvr {

class ScratchFile {
 public:
  explicit ScratchFile(const std::string& dir);
  ~ScratchFile();
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  void write(uint64_t offset, std::span<const std::byte> bytes);
  // Consecutive bytes from offset into the pieces, in order (one preadv:
  // a transpose reads a run of rows straight into the frames they belong to).
  void read(uint64_t offset, std::span<const std::span<std::byte>> pieces);

 private:
  [[noreturn]] void failWith(const char* what, int error) const;
  std::string dir_;
  int fd_ = -1;
};

}  // namespace mvr
