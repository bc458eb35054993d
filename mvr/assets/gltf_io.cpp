#include "mvr/assets/gltf_io.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "mvr/error.h"
#include "mvr/files/file_search.h"
#include "mvr/assets/assimp_import.h"
#include "mvr/assets/gltf_draco.h"
#include "mvr/assets/gltf_reader.h"
#include "mvr/assets/mesh_check.h"

namespace mvr {
namespace {

std::string firstLine(const std::string& s) {
  const size_t end = s.find('\n');
  std::string line = s.substr(0, end);
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  return line;
}

// A file's bytes mapped read-only for the life of the object.
class MappedFile {
 public:
  explicit MappedFile(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    struct stat st {};
    if (fd < 0 || ::fstat(fd, &st) != 0) {
      if (fd >= 0) ::close(fd);
      fail(path, "cannot read");
    }
    size_ = size_t(st.st_size);
    if (size_ > 0) data_ = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
    ::close(fd);
    if (data_ == MAP_FAILED) fail(path, "cannot read");
  }
  ~MappedFile() {
    if (data_ && data_ != MAP_FAILED) ::munmap(data_, size_);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  const unsigned char* bytes() const { return static_cast<const unsigned char*>(data_); }
  size_t size() const { return size_; }

 private:
  void* data_ = nullptr;
  size_t size_ = 0;
};

constexpr const char* kVersionOne = "glTF 1.0";

// tinygltf reads glTF 2.0 only; a glTF 1.0 file's meshes, nodes and
// materials are assimp's to read (its techniques' shaders are not run).
Scene loadVersionOne(const std::string& path) {
  Scene scene = importWithAssimp(path);
  scene.warnings.push_back(path + ": glTF 1.0, read by assimp: its materials as their colours and textures, unanimated");
  return scene;
}

// Extensions without which a file's meshes cannot be read at all.
bool isGeometryExtension(const std::string& e) {
  return e == "EXT_meshopt_compression";
}

std::string unreadExtension(const std::string& e) {
  return "needs the extension " + e + ", which is not read (re-export without mesh compression)";
}

// Why tinygltf refused a .gltf, where the file says it plainly: glTF 1
// ("version": "1.0", or the number 1, which tinygltf cannot read), or a
// compressed mesh tinygltf finds no data for. Empty where neither.
std::string refusal(const std::string& path) {
  if (lowerExtension(path) != ".gltf") return "";
  std::ifstream in(path);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (!j.is_object()) return "";
  if (j.contains("asset") && j["asset"].is_object() && j["asset"].contains("version")) {
    const nlohmann::json& v = j["asset"]["version"];
    if ((v.is_number() && v.get<double>() < 2.0) || (v.is_string() && v.get<std::string>().rfind('1', 0) == 0))
      return kVersionOne;
  }
  if (j.contains("extensionsRequired") && j["extensionsRequired"].is_array())
    for (const nlohmann::json& e : j["extensionsRequired"])
      if (e.is_string() && isGeometryExtension(e.get<std::string>())) return unreadExtension(e.get<std::string>());
  return "";
}

}  // namespace

bool isGltfPath(const std::string& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".gltf" || ext == ".glb";
}

Scene loadGltf(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "no such glTF file");
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  bool ok = false;
  if (lowerExtension(path) == ".glb") {
    // Mapped, not read: tinygltf's own file read zero-fills a buffer the
    // size of the file and copies the file into it, before it copies the
    // binary chunk again into its buffer (a 1M-triangle GLB: 24 MB).
    const MappedFile file(path);
    const unsigned char* bytes = file.bytes();
    const size_t size = file.size();
    if (size > 0xffffffffu) fail(path, "GLB file over 4 GiB");
    uint32_t declared = 0;
    if (size >= 12 && std::memcmp(bytes, "glTF", 4) == 0) std::memcpy(&declared, bytes + 8, 4);
    if (declared > size)
      fail(path, "GLB is cut: its header says " + std::to_string(declared) + " bytes, the file has " +
                     std::to_string(size));
    if (size >= 8 && std::memcmp(bytes, "glTF", 4) == 0 && bytes[4] == 1 && !bytes[5] && !bytes[6] && !bytes[7])
      return loadVersionOne(path);
    const std::string dir = std::filesystem::path(path).parent_path().string();
    ok = loader.LoadBinaryFromMemory(&model, &error, &warning, bytes, unsigned(size), dir);
    if (const std::string patched = ok ? "" : gltf::glbWithoutDracoIndices(bytes, size); !patched.empty()) {
      error.clear(), warning.clear();
      ok = loader.LoadBinaryFromMemory(&model, &error, &warning, reinterpret_cast<const unsigned char*>(patched.data()),
                                       unsigned(patched.size()), dir);
    }
  } else {
    ok = loader.LoadASCIIFromFile(&model, &error, &warning, path);
    if (!ok) {
      std::ifstream in(path, std::ios::binary);
      const std::string patched = gltf::withoutDracoIndices(std::string(std::istreambuf_iterator<char>(in), {}));
      if (!patched.empty()) {
        error.clear(), warning.clear();
        ok = loader.LoadASCIIFromString(&model, &error, &warning, patched.c_str(), unsigned(patched.size()),
                                        std::filesystem::path(path).parent_path().string());
      }
    }
  }
  if (!ok) {
    const std::string why = refusal(path);
    if (why == kVersionOne) return loadVersionOne(path);
    fail(path, !why.empty() ? why : error.empty() ? "cannot read glTF" : firstLine(error));
  }
  if (!model.asset.version.empty() && model.asset.version[0] == '1') return loadVersionOne(path);
  for (const std::string& e : model.extensionsRequired)
    if (isGeometryExtension(e)) fail(path, unreadExtension(e));
  Scene scene = gltf::GltfReader(model, path).read();
  if (!warning.empty()) scene.warnings.push_back(path + ": " + firstLine(warning));
  return scene;
}

}  // namespace mvr
