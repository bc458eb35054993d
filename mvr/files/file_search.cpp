#include "mvr/files/file_search.h"

#include <algorithm>
#include <cctype>
#include <system_error>

namespace mvr {

namespace fs = std::filesystem;

namespace {

// The path's parts from dir, each as written or else in another case.
std::string walk(const fs::path& dir, const fs::path& name, bool& caseDiffers) {
  std::error_code ec;
  fs::path at = name.is_absolute() ? name.root_path() : dir;
  for (const fs::path& part : name.relative_path()) {
    if (part == "." || part.empty()) continue;
    if (part == ".." || fs::exists(at / part, ec)) {
      at /= part;
      continue;
    }
    const std::string want = lowerCase(part.string());
    bool found = false;
    for (auto it = fs::directory_iterator(at, ec); !ec && it != fs::directory_iterator(); it.increment(ec))
      if (lowerCase(it->path().filename().string()) == want) {
        at = it->path(), found = caseDiffers = true;
        break;
      }
    if (!found) return "";
  }
  return fs::is_regular_file(at, ec) ? at.string() : "";
}

}  // namespace

std::string findFile(const fs::path& dir, const std::string& written, std::string& how, bool& backslashes) {
  std::error_code ec;
  how.clear();
  backslashes = false;
  const fs::path exact = dir / written;
  if (fs::is_regular_file(exact, ec)) return exact.string();
  std::string slashed = written;
  std::replace(slashed.begin(), slashed.end(), '\\', '/');
  const fs::path name(slashed);
  bool caseDiffers = false;
  std::string found = walk(dir, name, caseDiffers);
  // A path from the exporting machine ("D:\\textures\\wood.jpg"): the
  // file's name beside the model, where such files travel.
  if (found.empty() && name.has_parent_path()) {
    found = walk(dir, name.filename(), caseDiffers);
    caseDiffers = caseDiffers || !found.empty();
  }
  if (found.empty()) return "";
  if (caseDiffers) how = "as " + found;
  backslashes = slashed != written;
  return found;
}

std::string lowerCase(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string lowerExtension(const std::string& path) { return lowerCase(fs::path(path).extension().string()); }

}  // namespace mvr
