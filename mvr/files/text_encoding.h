#pragma once
// Text files saved as UTF-16 (Windows tools' "Unicode"), which the text
// readers take as UTF-8: told by their byte order mark, and transcoded.
#include <string>

namespace mvr {

// Whether the bytes start with a UTF-16 byte order mark (FE FF or FF FE).
bool isUtf16(const std::string& start);
// The whole file's UTF-16 text (its mark telling the byte order) as UTF-8,
// without the mark; an unpaired surrogate becomes U+FFFD. Throws
// mvr::Error naming the file if it cannot be read.
std::string utf8OfUtf16File(const std::string& path);
// The first `n` bytes of a file (fewer if it is shorter; none if unreadable).
std::string fileStart(const std::string& path, size_t n);

}  // namespace mvr
