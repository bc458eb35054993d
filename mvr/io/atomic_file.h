#pragma once
// A file that appears complete or not at all: written under a temporary
// name beside it, every write and the close checked, then renamed into
// place. Image files and manifests go through it, so a full disk or a
// file-size limit is an error naming the file and the system's reason,
// never a truncated file that looks finished.
#include <cstddef>
#include <span>
#include <string>

namespace mvr {

// Throws mvr::Error "PATH: cannot write: REASON"; the temporary file is
// removed on failure.
void writeFileAtomically(const std::string& path, std::span<const std::byte> bytes);

}  // namespace mvr
