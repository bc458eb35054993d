#include "mvr/assets/assimp_import.h"

#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mvr/error.h"
#include "mvr/image.h"
#include "mvr/files/file_search.h"
#include "mvr/files/helper_program.h"
#include "mvr/images/image_file.h"
#include "mvr/assets/imported_model.h"
#include "mvr/assets/load_warnings.h"
#include "mvr/assets/mesh_check.h"
#include "mvr/files/text_encoding.h"

namespace mvr {
namespace {

namespace fs = std::filesystem;

constexpr int kTimeoutSeconds = 300;

// The importer's time limit: kTimeoutSeconds, or MVR_IMPORT_SECONDS (1 to
// kTimeoutSeconds) where set: the fuzzer's limit per input is 10 s, and an
// importer that hangs is assimp's defect, which this process must survive.
int importSeconds() {
  const char* set = std::getenv("MVR_IMPORT_SECONDS");
  const int seconds = set ? std::atoi(set) : 0;
  return seconds >= 1 && seconds <= kTimeoutSeconds ? seconds : kTimeoutSeconds;
}
constexpr size_t kMaxOutput = size_t(8) << 30;

struct ChildOutput {
  std::string out, err;
  int status = 0;
  bool timedOut = false;
};

// Runs helper FILE, reading its stdout and stderr to the end (or the
// time limit, when it is killed).
ChildOutput run(const std::string& helper, const std::string& path) {
  const HelperProcess child = spawnHelper({helper, path}, HelperPipe::Stdout, path);
  const pid_t pid = child.pid;
  ChildOutput result;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(importSeconds());
  pollfd fds[2] = {{child.stream, POLLIN, 0}, {child.errors, POLLIN, 0}};
  std::string* sinks[2] = {&result.out, &result.err};
  char buffer[1 << 16];
  for (int open = 2; open > 0;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0 || result.out.size() > kMaxOutput) {
      result.timedOut = left.count() <= 0;
      kill(pid, SIGKILL);
      break;
    }
    if (poll(fds, 2, int(left.count())) < 0 && errno != EINTR) break;
    for (int k = 0; k < 2; ++k) {
      if (fds[k].fd < 0 || !(fds[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      const ssize_t n = read(fds[k].fd, buffer, sizeof buffer);
      if (n > 0) {
        sinks[k]->append(buffer, size_t(n));
      } else if (n == 0 || errno != EINTR) {
        close(fds[k].fd);
        fds[k].fd = -1;
        --open;
      }
    }
  }
  for (const pollfd& f : fds)
    if (f.fd >= 0) close(f.fd);
  result.status = waitHelper(pid);
  return result;
}

std::string firstLine(const std::string& s) {
  std::string line = s.substr(0, s.find('\n'));
  return line.substr(0, 300);
}

// An embedded image decoded: encoded bytes through a temporary file (the
// image codec reads files), texels as they are.
std::shared_ptr<const Image> decode(const EmbeddedImage& e) {
  if (e.width > 0 && e.height > 0) {
    if (e.bytes.size() < size_t(e.width) * e.height * 4) return nullptr;
    auto img = std::make_shared<Image>(e.width, e.height, PixelType::Srgb8);
    for (size_t i = 0; i < size_t(e.width) * e.height; ++i) {
      const uint8_t* bgra = &e.bytes[4 * i];
      uint8_t* rgba = &img->bytes[4 * i];
      rgba[0] = bgra[2], rgba[1] = bgra[1], rgba[2] = bgra[0], rgba[3] = bgra[3];
    }
    return img;
  }
  std::string hint;
  for (char c : e.hint)
    if (std::isalnum(static_cast<unsigned char>(c))) hint += c;
  std::string name = (fs::temp_directory_path() / "mvr_embedded_XXXXXX").string() + "." + (hint.empty() ? "png" : hint);
  const int fd = mkstemps(name.data(), int(hint.empty() ? 4 : hint.size() + 1));
  if (fd < 0) return nullptr;
  close(fd);
  std::ofstream(name, std::ios::binary).write(reinterpret_cast<const char*>(e.bytes.data()), std::streamsize(e.bytes.size()));
  std::shared_ptr<const Image> img;
  try {
    img = std::make_shared<const Image>(readImage(name));
  } catch (const Error&) {
  }
  std::error_code ec;
  fs::remove(name, ec);
  return img;
}

// Each material's texture: an embedded image ("*K"), or a file beside
// the model; what cannot be had is a warning, and the surface untextured.
void resolveTextures(ImportedModel& model, const std::string& path) {
  Scene& s = model.scene;
  LoadWarnings warn(s, path);
  const fs::path dir = fs::path(path).parent_path();
  std::vector<std::shared_ptr<const Image>> decoded(model.embedded.size());
  for (Material& m : s.materials) {
    if (m.texture.empty()) continue;
    const std::string written = m.texture;
    m.texture.clear();
    if (written[0] == '*') {
      const size_t k = std::strtoul(written.c_str() + 1, nullptr, 10);
      if (k < decoded.size() && !decoded[k]) decoded[k] = decode(model.embedded[k]);
      if (k < decoded.size() && decoded[k]) {
        m.textureImage = decoded[k];
        m.texture = path + "#image" + std::to_string(k);
      } else {
        warn("embedded image " + written + " could not be decoded: drawn untextured");
      }
      continue;
    }
    std::string how;
    bool backslashes = false;
    m.texture = findFile(dir, written, how, backslashes);
    if (m.texture.empty()) warn("texture '" + written + "' not found: drawn untextured");
    if (!how.empty()) warn("texture '" + written + "' read " + how);
  }
}

// Collada lists a number list's values between blanks, leading ones
// included (xs:list); assimp's reader takes the first blank for a number
// ("Cannot parse string \"  0.0 ...\""). Blanks that open a <color> or
// <float> value are dropped. Returns whether any were.
bool trimLeadingBlanks(std::string& text) {
  bool trimmed = false;
  for (const std::string tag : {"<color", "<float>"}) {
    for (size_t at = text.find(tag); at != std::string::npos; at = text.find(tag, at + 1)) {
      const size_t open = text.find('>', at);
      if (open == std::string::npos) break;
      const size_t value = text.find_first_not_of(" \t\r\n", open + 1);
      if (value == std::string::npos || value == open + 1 || text[value] == '<') continue;
      text.erase(open + 1, value - open - 1);
      trimmed = true;
    }
  }
  return trimmed;
}

// Each element <tag ...>...</tag> removed from text.
void eraseElements(std::string& text, const std::string& tag) {
  for (size_t at = text.find("<" + tag); at != std::string::npos; at = text.find("<" + tag, at)) {
    const size_t end = text.find("</" + tag + ">", at);
    if (end == std::string::npos) return;
    text.erase(at, end + tag.size() + 3 - at);
  }
}

// The value of attribute name in the tag that opens at `at`, or "".
std::string attribute(const std::string& text, size_t at, const std::string& name) {
  const size_t close = text.find('>', at), key = text.find(" " + name + "=\"", at);
  if (key == std::string::npos || key > close) return "";
  const size_t value = key + name.size() + 3, end = text.find('"', value);
  return end == std::string::npos ? "" : text.substr(value, end - value);
}

// Collada's controllers (a skin or a morph over a geometry) as the
// geometry they deform, for a file whose skins assimp cannot read: each
// <instance_controller url="#C"> becomes <instance_geometry url="#G">, G
// the source of C's skin or morph, its <skeleton>s dropped, and the
// controllers removed. Returns whether any instance was replaced.
bool controllersAsGeometry(std::string& text) {
  std::map<std::string, std::string> source;  // controller id -> geometry url
  for (size_t at = text.find("<controller "); at != std::string::npos; at = text.find("<controller ", at + 1)) {
    const size_t skin = std::min(text.find("<skin ", at), text.find("<morph ", at));
    if (skin == std::string::npos) continue;
    std::string url(1, '#');  // built up: GCC 12 warns of "#" + string (-Wrestrict)
    source[url.append(attribute(text, at, "id"))] = attribute(text, skin, "source");
  }
  eraseElements(text, "library_controllers");
  bool replaced = false;
  const std::string open = "<instance_controller", close = "</instance_controller>";
  for (size_t at = text.find(open); at != std::string::npos; at = text.find(open, at)) {
    const auto geometry = source.find(attribute(text, at, "url"));
    if (geometry == source.end() || geometry->second.empty()) return false;
    const size_t tagEnd = text.find('>', at);
    const bool empty = text[tagEnd - 1] == '/';
    text.replace(at, tagEnd + 1 - at, "<instance_geometry url=\"" + geometry->second + (empty ? "\"/>" : "\">"));
    replaced = true;
  }
  for (size_t at = text.find(close); at != std::string::npos; at = text.find(close, at))
    text.replace(at, close.size(), "</instance_geometry>");
  eraseElements(text, "skeleton");
  return replaced;
}

// A binary FBX starts "Kaydara FBX Binary  " and the bytes 0, 0x1a, 0. A
// file whose zero bytes all became blanks went through a text transfer.
void checkFbxHeader(const std::string& path) {
  const std::string head = fileStart(path, 23);
  if (head.rfind("Kaydara FBX Binary", 0) == 0 && head.size() == 23 && head[20] != '\0')
    fail(path, "binary FBX with its zero bytes replaced (byte 20 is " + std::to_string(int(uint8_t(head[20]))) +
                   ", not 0): the file was damaged in a text transfer");
}

// What assimp is given to read: the file, or a UTF-8 copy in a folder of
// its own, removed with this object, where its text is UTF-16 (assimp's
// XML reader takes UTF-8) or a Collada number list opens with blanks.
// Textures are still found from the file.
class ReadableCopy {
 public:
  // unskinned: a Collada file's controllers as their geometry
  // (controllersAsGeometry).
  explicit ReadableCopy(const std::string& path, bool unskinned = false) : path_(path) {
    const bool utf16 = isUtf16(fileStart(path, 2)), collada = lowerExtension(path) == ".dae";
    if (!utf16 && !collada) return;
    std::string text = utf16 ? utf8OfUtf16File(path) : contents(path);
    if (utf16) {
      // Its XML declaration says UTF-16; the copy is not.
      const size_t end = text.rfind("?>", 200);
      if (text.rfind("<?xml", 0) == 0 && end != std::string::npos) {
        const size_t at = text.find("UTF-16"), low = text.find("utf-16");
        const size_t which = std::min(at, low);
        if (which < end) text.replace(which, 6, "UTF-8");
      }
      notes_.push_back("UTF-16 text read as UTF-8");
    }
    if (collada && trimLeadingBlanks(text)) notes_.push_back("blanks before number lists dropped for assimp");
    undeformed_ = collada && unskinned && controllersAsGeometry(text);
    if (undeformed_)
      notes_.push_back("assimp failed on its skins and morphs: drawn undeformed, in the pose they bind to, unanimated");
    if (notes_.empty()) return;
    std::string dir = (fs::temp_directory_path() / "mvr-import-XXXXXX").string();
    if (!::mkdtemp(dir.data())) fail(path, "cannot make a folder for its copy");
    dir_ = dir;
    path_ = (fs::path(dir) / fs::path(path).filename()).string();
    std::ofstream out(path_, std::ios::binary);
    out << text;
    if (!out.flush()) fail(path, "cannot write its copy in " + dir);
  }
  ~ReadableCopy() {
    std::error_code ec;
    if (!dir_.empty()) fs::remove_all(dir_, ec);
  }
  ReadableCopy(const ReadableCopy&) = delete;
  ReadableCopy& operator=(const ReadableCopy&) = delete;
  const std::string& path() const { return path_; }
  // What the copy changed, for the scene's warnings.
  const std::vector<std::string>& notes() const { return notes_; }
  // Whether the copy has a Collada file's controllers as their geometry.
  bool undeformed() const { return undeformed_; }

 private:
  static std::string contents(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  std::string path_, dir_;
  std::vector<std::string> notes_;
  bool undeformed_ = false;
};

}  // namespace

bool isAssimpPath(const std::string& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".fbx" || ext == ".dae" || ext == ".3ds";
}

Scene importWithAssimp(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) fail(path, "no such model file");
  if (lowerExtension(path) == ".fbx") checkFbxHeader(path);
  const std::string helper = helperProgram("mvr-import", "MVR_IMPORT", path, "FBX, Collada and 3DS files are read");
  std::optional<ReadableCopy> text(std::in_place, path);
  ChildOutput child = run(helper, text->path());
  // Assimp 5.2's Collada skins can fail it outright (out of memory, a
  // crash) on files that are well formed: then the meshes they deform.
  const bool failed = WIFSIGNALED(child.status) || firstLine(child.err) == "std::bad_alloc";
  if (failed && !child.timedOut && lowerExtension(path) == ".dae") {
    if (text.emplace(path, true).undeformed()) child = run(helper, text->path());
  }
  if (child.timedOut) fail(path, "the importer (assimp) took more than " + std::to_string(importSeconds()) + " s");
  if (WIFSIGNALED(child.status))
    fail(path, "the importer (assimp) failed on this file (signal " + std::to_string(WTERMSIG(child.status)) +
                   (WTERMSIG(child.status) == SIGXCPU ? ": its CPU time limit)" : ")"));
  if (!WIFEXITED(child.status) || WEXITSTATUS(child.status) != 0)
    fail(path, child.err.empty()                    ? "the importer (assimp) could not read it"
               : firstLine(child.err) == "std::bad_alloc" ? "the importer (assimp) ran out of memory reading it"
                                                          : firstLine(child.err));
  ImportedModel model = readImportedModel(child.out, path);
  for (std::string& w : model.scene.warnings) w = path + ": " + w;
  for (const std::string& note : text->notes()) model.scene.warnings.push_back(path + ": " + note);
  resolveTextures(model, path);
  if (model.scene.triangles.empty()) fail(path, "mesh has no triangles");
  return std::move(model.scene);
}

}  // namespace mvr
