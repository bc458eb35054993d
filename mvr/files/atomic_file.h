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

// The same file written in pieces over time (a view's PNG bytes as its
// rows are encoded, when they may not all be held): the first piece
// creates the temporary file, each piece opens, appends and closes it (no
// descriptor held between pieces, whatever the number of files), and the
// last renames it into place. Errors as writeFileAtomically's, the
// temporary file removed. removePart drops an unfinished file.
void appendToPart(const std::string& path, std::span<const std::byte> bytes, bool first);
void finishPart(const std::string& path, std::span<const std::byte> last);
void removePart(const std::string& path);
// For a file another writer fills under the temporary name (a stream's
// descriptor, a split job's shared file): the name, and the rename into
// place once it is complete (errors as above, the temporary file removed).
std::string partName(const std::string& path);
void commitPart(const std::string& path);

}  // namespace mvr
