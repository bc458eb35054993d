#include "mvr/files/text_encoding.h"

#include <fstream>
#include <iterator>

#include "mvr/error.h"

namespace mvr {
namespace {

void appendUtf8(std::string& out, char32_t c) {
  if (c < 0x80) {
    out += char(c);
  } else if (c < 0x800) {
    out += char(0xc0 | c >> 6), out += char(0x80 | (c & 0x3f));
  } else if (c < 0x10000) {
    out += char(0xe0 | c >> 12), out += char(0x80 | (c >> 6 & 0x3f)), out += char(0x80 | (c & 0x3f));
  } else {
    out += char(0xf0 | c >> 18), out += char(0x80 | (c >> 12 & 0x3f)), out += char(0x80 | (c >> 6 & 0x3f)),
        out += char(0x80 | (c & 0x3f));
  }
}

}  // namespace

bool isUtf16(const std::string& start) {
  return start.size() >= 2 && ((start[0] == '\xfe' && start[1] == '\xff') || (start[0] == '\xff' && start[1] == '\xfe'));
}

std::string fileStart(const std::string& path, size_t n) {
  std::ifstream in(path, std::ios::binary);
  std::string s(n, '\0');
  in.read(s.data(), std::streamsize(n));
  s.resize(size_t(std::max<std::streamsize>(in.gcount(), 0)));
  return s;
}

std::string utf8OfUtf16File(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot read");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const bool big = bytes.size() >= 2 && bytes[0] == '\xfe';
  auto unit = [&](size_t i) {
    const auto a = uint16_t(uint8_t(bytes[i])), b = uint16_t(uint8_t(bytes[i + 1]));
    return big ? uint16_t(a << 8 | b) : uint16_t(b << 8 | a);
  };
  std::string out;
  out.reserve(bytes.size() / 2);
  for (size_t i = 2; i + 1 < bytes.size(); i += 2) {
    const uint16_t u = unit(i);
    if (u >= 0xd800 && u < 0xdc00 && i + 3 < bytes.size() && unit(i + 2) >= 0xdc00 && unit(i + 2) < 0xe000) {
      appendUtf8(out, 0x10000 + (char32_t(u - 0xd800) << 10) + (unit(i + 2) - 0xdc00));
      i += 2;
    } else {
      appendUtf8(out, u >= 0xd800 && u < 0xe000 ? char32_t(0xfffd) : char32_t(u));
    }
  }
  return out;
}

}  // namespace mvr
