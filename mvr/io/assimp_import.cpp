#include "mvr/io/assimp_import.h"

#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>

#include "mvr/error.h"
#include "mvr/image.h"
#include "mvr/io/file_search.h"
#include "mvr/io/helper_program.h"
#include "mvr/io/image_file.h"
#include "mvr/io/imported_model.h"
#include "mvr/io/load_warnings.h"
#include "mvr/io/mesh_check.h"
#include "mvr/io/text_encoding.h"

namespace mvr {
namespace {

namespace fs = std::filesystem;

constexpr int kTimeoutSeconds = 300;
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
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(kTimeoutSeconds);
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

// What assimp is given to read: the file, or where its text is UTF-16
// (assimp's XML reader takes UTF-8) a UTF-8 copy in a folder of its own,
// removed with this object. Textures are still found from the file.
class Utf8Copy {
 public:
  explicit Utf8Copy(const std::string& path) : path_(path) {
    if (!isUtf16(fileStart(path, 2))) return;
    std::string text = utf8OfUtf16File(path);
    // Its XML declaration says UTF-16; the copy is not.
    const size_t end = text.rfind("?>", 200);
    if (text.rfind("<?xml", 0) == 0 && end != std::string::npos) {
      const size_t at = text.find("UTF-16"), low = text.find("utf-16");
      const size_t which = std::min(at, low);
      if (which < end) text.replace(which, 6, "UTF-8");
    }
    std::string dir = (fs::temp_directory_path() / "mvr-import-XXXXXX").string();
    if (!::mkdtemp(dir.data())) fail(path, "cannot make a folder for its UTF-8 copy");
    dir_ = dir;
    path_ = (fs::path(dir) / fs::path(path).filename()).string();
    std::ofstream out(path_, std::ios::binary);
    out << text;
    if (!out.flush()) fail(path, "cannot write its UTF-8 copy in " + dir);
  }
  ~Utf8Copy() {
    std::error_code ec;
    if (!dir_.empty()) fs::remove_all(dir_, ec);
  }
  Utf8Copy(const Utf8Copy&) = delete;
  Utf8Copy& operator=(const Utf8Copy&) = delete;
  const std::string& path() const { return path_; }
  bool transcoded() const { return !dir_.empty(); }

 private:
  std::string path_, dir_;
};

}  // namespace

bool isAssimpPath(const std::string& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".fbx" || ext == ".dae" || ext == ".3ds";
}

Scene importWithAssimp(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) fail(path, "no such model file");
  const Utf8Copy text(path);
  const ChildOutput child =
      run(helperProgram("mvr-import", "MVR_IMPORT", path, "FBX, Collada and 3DS files are read"), text.path());
  if (child.timedOut) fail(path, "the importer (assimp) took more than " + std::to_string(kTimeoutSeconds) + " s");
  if (WIFSIGNALED(child.status))
    fail(path, "the importer (assimp) failed on this file (signal " + std::to_string(WTERMSIG(child.status)) +
                   (WTERMSIG(child.status) == SIGXCPU ? ": its CPU time limit)" : ")"));
  if (!WIFEXITED(child.status) || WEXITSTATUS(child.status) != 0)
    fail(path, child.err.empty() ? "the importer (assimp) could not read it" : firstLine(child.err));
  ImportedModel model = readImportedModel(child.out, path);
  for (std::string& w : model.scene.warnings) w = path + ": " + w;
  if (text.transcoded()) model.scene.warnings.push_back(path + ": UTF-16 text read as UTF-8");
  resolveTextures(model, path);
  if (model.scene.triangles.empty()) fail(path, "mesh has no triangles");
  return std::move(model.scene);
}

}  // namespace mvr
