#include "mvr/assets/mesh_check.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string_view>
#include <vector>

#include "mvr/error.h"
#include "mvr/files/file_search.h"

namespace mvr {
namespace {

[[noreturn]] void failAt(const std::string& path, long line, const std::string& what) {
  fail(path + ":" + std::to_string(line), what);
}

// The whole word as a number of type T; false for an empty word, junk, a
// value out of T's range, or trailing characters.
template <class T>
bool parseWhole(std::string_view word, T& value) {
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
  return !word.empty() && ec == std::errc() && end == word.data() + word.size();
}

// One face corner "v", "v/vt", "v//vn" or "v/vt/vn" against the counts so
// far; returns its vertex, counted from 1.
long checkCorner(const std::string& path, long line, const std::string& corner, const long (&defined)[3]) {
  static const char* const kWhat[3] = {"vertex", "texture coordinate", "normal"};
  long vertex = 0;
  size_t at = 0;
  for (int k = 0; k < 3 && at <= corner.size(); ++k) {
    const size_t slash = corner.find('/', at);
    const std::string field = corner.substr(at, slash == std::string::npos ? std::string::npos : slash - at);
    at = slash == std::string::npos ? corner.size() + 1 : slash + 1;
    if (field.empty()) {
      if (k == 0) failAt(path, line, "face corner '" + corner + "' has no vertex index");
      continue;
    }
    long index = 0;
    if (!parseWhole(field, index) || index == 0)
      failAt(path, line, "bad face index '" + field + "'");
    const long resolved = index > 0 ? index : defined[k] + 1 + index;
    if (resolved < 1 || resolved > defined[k])
      failAt(path, line, "face refers to " + std::string(kWhat[k]) + " " + std::to_string(index) + " but " +
                             std::to_string(defined[k]) + " are defined before it");
    if (k == 0) vertex = resolved;
  }
  return vertex;
}

// The first `count` numbers of a v, vt or vn line: finite, and within
// kMaxCoordinate so that float holds them. OpenMesh's reader drops a line
// whose number does not parse as a float ("nan", "1e300") and so shifts
// every index after it: faces then name elements out of range.
void checkNumbers(const std::string& path, long line, std::istringstream& words, int count, const char* what) {
  for (int k = 0; k < count; ++k) {
    std::string word;
    words >> word;
    double value = 0.0;
    const std::string_view digits = std::string_view(word).substr(word.size() > 1 && word[0] == '+');  // from_chars takes no '+'
    if (!parseWhole(digits, value) || !(std::abs(value) <= kMaxCoordinate))
      failAt(path, line, std::string(what) + " '" + word + "' is not a finite number within 1e15");
  }
}

// The statements tinyobjloader reads into what we draw; "l" and "p" it
// reads as points and lines, which we skip.
bool isDrawnObjStatement(const std::string& key) {
  static const char* const kDrawn[] = {"v", "vt", "vn", "f", "g", "o", "s", "usemtl", "mtllib"};
  return std::find_if(std::begin(kDrawn), std::end(kDrawn), [&](const char* k) { return key == k; }) != std::end(kDrawn);
}

// How many distinct statement keywords a file's warning names at most (a
// fuzzed file has thousands).
constexpr size_t kMaxIgnoredNamed = 8;

void noteObjStatement(const std::string& key, long line, ObjStatements& notes) {
  if (key == "l" || key == "p") {
    notes.pointsOrLines = true;
    return;
  }
  if (isDrawnObjStatement(key)) return;
  for (const auto& [known, first] : notes.ignored)
    if (known == key) return;
  if (notes.ignored.size() < kMaxIgnoredNamed) notes.ignored.emplace_back(key.substr(0, 24), line);
}

}  // namespace

void checkObjFile(const std::string& path, ObjStatements* notes) {
  std::ifstream in(path);
  checkObjText(in, path, notes);
}

void checkObjText(std::istream& in, const std::string& path, ObjStatements* notes) {
  std::vector<long> corners;
  long defined[3] = {0, 0, 0};  // v, vt, vn
  long line = 0;
  for (std::string text; std::getline(in, text);) {
    if (++line == 1 && text.size() >= 2 && ((text[0] == '\xfe' && text[1] == '\xff') || (text[0] == '\xff' && text[1] == '\xfe')))
      fail(path, "UTF-16 text is not read (save the OBJ as UTF-8)");
    // Trim blanks, then skip a line that is empty, a comment, or starts
    // with other white space (a form feed), as OpenMesh's reader did.
    const size_t first = text.find_first_not_of(" \t\r\n");
    if (first == std::string::npos || text[first] == '#' || std::isspace(static_cast<unsigned char>(text[first])))
      continue;
    std::istringstream words(text.substr(first));
    std::string key;
    words >> key;
    if (key == "v") {
      ++defined[0];
      checkNumbers(path, line, words, 3, "vertex coordinate");
    } else if (key == "vt") {
      ++defined[1];
      checkNumbers(path, line, words, 2, "texture coordinate");
    } else if (key == "vn") {
      ++defined[2];
      checkNumbers(path, line, words, 3, "normal component");
    } else if (key == "f") {
      corners.clear();
      for (std::string corner; words >> corner;) corners.push_back(checkCorner(path, line, corner, defined));
      if (corners.size() < 3)
        failAt(path, line, "face with " + std::to_string(corners.size()) + " corners (needs 3)");
    } else if (key == "usemtl" && notes) {
      std::string more;
      notes->spacedNames = notes->spacedNames || (words >> more >> more);
    } else if (notes) {
      noteObjStatement(key, line, *notes);
    }
  }
}

namespace {

int plyTypeBytes(const std::string& type) {
  static const std::map<std::string, int> kBytes{
      {"char", 1},  {"uchar", 1},  {"int8", 1},   {"uint8", 1},   {"short", 2},   {"ushort", 2},
      {"int16", 2}, {"uint16", 2}, {"int", 4},    {"uint", 4},    {"int32", 4},   {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto it = kBytes.find(type);
  return it == kBytes.end() ? 0 : it->second;
}

size_t countWords(const std::string& text) {
  std::istringstream words(text);
  size_t n = 0;
  for (std::string word; words >> word;) ++n;
  return n;
}

// One property of a PLY element: a scalar of `type`, or a list whose count
// has `type` and whose items have itemBytes each.
struct PlyProperty {
  bool list;
  std::string type;
  int itemBytes;
};

// A binary list count of its type (1, 2 or 4 bytes; signed or not).
long long plyListCount(const unsigned char* raw, int bytes, const std::string& type, bool bigEndian) {
  unsigned long value = 0;
  for (int k = 0; k < bytes; ++k) value |= static_cast<unsigned long>(raw[bigEndian ? bytes - 1 - k : k]) << (8 * k);
  const bool isSigned = type == "char" || type == "int8" || type == "short" || type == "int16" || type == "int" ||
                        type == "int32";
  if (isSigned && (value >> (8 * bytes - 1)) & 1) return -1;
  return static_cast<long long>(value);
}

// One ASCII element line: a token per scalar; per list a count (an integer
// its count type holds) and that many items, all on the line.
void checkPlyAsciiElement(const std::string& path, long line, const std::string& text,
                          const std::vector<PlyProperty>& properties) {
  std::istringstream words(text);
  std::string word;
  for (const PlyProperty& p : properties) {
    if (!(words >> word)) failAt(path, line, "element line has fewer values than its properties");
    if (!p.list) continue;
    unsigned long long items = 0;
    const int bytes = plyTypeBytes(p.type);
    const unsigned long long most = bytes >= 4 ? (1ull << 31) - 1 : (1ull << (8 * bytes)) - 1;
    if (!parseWhole(word, items) || items > most)
      failAt(path, line, "bad list count '" + word + "'");
    for (unsigned long long k = 0; k < items; ++k)
      if (!(words >> word)) failAt(path, line, "list of " + std::to_string(items) + " items does not fit its line");
  }
}

// OpenMesh reads the header word by word and stops only at "end_header":
// within an obj_info line these words would be read as statements.
bool holdsHeaderKeyword(const std::string& text) {
  std::istringstream words(text);
  for (std::string word; words >> word;)
    if (word == "element" || word == "property" || word == "end_header") return true;
  return false;
}

void checkPly(const std::string& path, PlyCommentLines* comments) {
  constexpr size_t kMaxHeader = 1 << 16;
  std::ifstream in(path, std::ios::binary);
  struct Element {
    std::string name;
    unsigned long long count;
    unsigned long long fixedBytes = 0;  // per element, list items not counted
    std::vector<PlyProperty> properties;
  };
  std::vector<Element> elements;
  std::string format;
  long line = 0;
  bool ended = false;
  for (std::string text; !ended && std::getline(in, text);) {
    ++line;
    if (in.tellg() > std::streamoff(kMaxHeader)) failAt(path, line, "PLY header longer than 64 KiB");
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (in.eof() && text != "end_header") break;  // an unterminated last line: the file was cut
    std::istringstream words(text);
    std::string key;
    words >> key;
    if (line == 1) {
      if (key != "ply") fail(path, "not a PLY file (no 'ply' on the first line)");
      continue;
    }
    // OpenMesh takes the second line's words as the format, whatever they are.
    if (line == 2 && key != "format") failAt(path, line, "the PLY format line must follow 'ply', not '" + key + "'");
    // OpenMesh reads the header word by word, not line by line: a line with
    // more words than its keyword takes would be read differently there
    // (an element count taken from the next line's words: gigabytes).
    const size_t wordCount = countWords(text);
    std::string second;
    std::istringstream(text) >> second >> second;
    const size_t expected = key == "format" || key == "element" ? 3
                            : key == "property"                 ? (second == "list" ? 5 : 3)
                            : key == "end_header"               ? 1
                                                                : wordCount;
    if (wordCount != expected)
      failAt(path, line, "PLY header line '" + key + "' has " + std::to_string(wordCount) + " words, expected " +
                             std::to_string(expected));
    if (key == "format") {
      std::string version;
      words >> format >> version;
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
        failAt(path, line, "unknown PLY format '" + format + "'");
      // OpenMesh's probe reads the version as a float and spins on anything
      // else: "nan", "inf" or 1e39 as well as junk.
      float number = 0.0f;
      if (!parseWhole(version, number) || !std::isfinite(number))
        failAt(path, line, "bad PLY version '" + version + "'");
    } else if (key == "element") {
      Element e;
      std::string count;
      words >> e.name >> count;
      if (e.name.empty() || !parseWhole(count, e.count) || e.count > (1ull << 31))
        failAt(path, line, "bad element line '" + text + "'");
      elements.push_back(e);
    } else if (key == "property") {
      if (elements.empty()) failAt(path, line, "property before any element");
      std::string type, countType, itemType;
      words >> type;
      if (type == "list") {
        words >> countType >> itemType;
        if (!plyTypeBytes(countType) || !plyTypeBytes(itemType) || countType == "float" ||
            countType == "float32" || countType == "double" || countType == "float64")
          failAt(path, line, "bad list property '" + text + "'");
        elements.back().fixedBytes += plyTypeBytes(countType);
        elements.back().properties.push_back({true, countType, plyTypeBytes(itemType)});
      } else {
        if (!plyTypeBytes(type)) failAt(path, line, "unknown property type '" + type + "'");
        elements.back().fixedBytes += plyTypeBytes(type);
        elements.back().properties.push_back({false, type, 0});
      }
    } else if (key == "end_header") {
      ended = true;
    } else if (key == "obj_info" && holdsHeaderKeyword(text)) {
      if (!comments) failAt(path, line, "PLY obj_info line holds a header keyword");
      comments->info.push_back(line);
    } else if (key != "comment" && key != "obj_info" && !key.empty()) {
      if (!comments) failAt(path, line, "unknown PLY header keyword '" + key + "'");
      comments->bare.push_back(line);
    }
  }
  if (!ended) fail(path, "PLY header has no end_header (file cut short)");
  for (const Element& e : elements)
    if (e.fixedBytes == 0 && e.count > 0) fail(path, "PLY element '" + e.name + "' has no properties");
  if (format.empty()) fail(path, "PLY header has no format line");
  const std::streamoff dataStart = in.tellg();
  const auto size = std::streamoff(std::filesystem::file_size(path));
  // Walk the data as OpenMesh will, so that no list count can make it read
  // or allocate past what the file holds (a count of 1e18 in an ASCII face
  // line spun forever; found by fuzzing).
  if (format == "ascii") {
    unsigned long long needed = 0, have = 0;
    for (const Element& e : elements) needed += e.count;
    for (const Element& e : elements) {
      for (unsigned long long i = 0; i < e.count; ++i) {
        std::string text;
        do {
          if (!std::getline(in, text))
            fail(path, "PLY data is cut: " + std::to_string(have) + " of " + std::to_string(needed) +
                           " element lines");
          ++line;
        } while (text.find_first_not_of(" \t\r") == std::string::npos);
        ++have;
        checkPlyAsciiElement(path, line, text, e.properties);
      }
    }
    return;
  }
  unsigned long long needed = 0;
  for (const Element& e : elements) needed += e.count * e.fixedBytes;
  if (static_cast<unsigned long long>(size - dataStart) < needed)
    fail(path, "PLY data is cut: its elements need at least " + std::to_string(needed) + " bytes, the file has " +
                   std::to_string(size - dataStart));
  // Sequentially from the data's start: a seek per face would cost seconds
  // for meshes of millions of faces.
  unsigned long long at = static_cast<unsigned long long>(dataStart);
  const auto end = static_cast<unsigned long long>(size);
  const bool bigEndian = format == "binary_big_endian";
  in.clear();
  in.seekg(dataStart);
  for (const Element& e : elements) {
    const bool hasList = std::any_of(e.properties.begin(), e.properties.end(), [](const PlyProperty& p) { return p.list; });
    if (!hasList) {  // fixed size, within the file: checked above
      in.ignore(std::streamsize(e.count * e.fixedBytes));
      at += e.count * e.fixedBytes;
      continue;
    }
    for (unsigned long long i = 0; i < e.count; ++i)
      for (const PlyProperty& p : e.properties) {
        const unsigned bytes = unsigned(plyTypeBytes(p.type));
        if (at + bytes > end) fail(path, "PLY data is cut in " + e.name + " " + std::to_string(i));
        at += bytes;
        if (!p.list) {
          in.ignore(bytes);
          continue;
        }
        unsigned char raw[4] = {0, 0, 0, 0};
        in.read(reinterpret_cast<char*>(raw), bytes);
        const long long items = plyListCount(raw, int(bytes), p.type, bigEndian);
        const unsigned long long itemBytes = static_cast<unsigned long long>(items) * unsigned(p.itemBytes);
        if (items < 0 || at + itemBytes > end)
          fail(path, "PLY " + e.name + " " + std::to_string(i) + " has a list of " + std::to_string(items) +
                         " items beyond the end of the file");
        in.ignore(std::streamsize(itemBytes));
        at += itemBytes;
      }
  }
}

// The next line that is neither blank nor a comment; false at the end.
bool nextDataLine(std::istream& in, std::string& text, long& line) {
  while (std::getline(in, text)) {
    ++line;
    const size_t first = text.find_first_not_of(" \t\r");
    if (first != std::string::npos && text[first] != '#') return true;
  }
  return false;
}

// OFF (ASCII, 3D, optionally with colours, normals or texture coordinates
// per vertex): counts, then a line per vertex whose first three numbers are
// finite, then a line per face whose corner count is at least 3 and whose
// corners exist. OpenMesh's reader trusts the counts: a corner count of 1e9
// allocates gigabytes, a vertex count of 4e8 reserves them.
void checkOff(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string text;
  long line = 0;
  if (!nextDataLine(in, text, line)) fail(path, "empty OFF file");
  std::istringstream header(text);
  std::string magic;
  header >> magic;
  if (magic.size() < 3 || magic.compare(magic.size() - 3, 3, "OFF") != 0) fail(path, "not an OFF file (no 'OFF' first)");
  if (magic.find_first_of("4n") != std::string::npos || text.find("BINARY") != std::string::npos)
    failAt(path, line, "'" + text + "': only ASCII OFF of 3D vertices is read");
  // The counts come on a line of their own, as OpenMesh reads them.
  unsigned long long vertices = 0, faces = 0;
  if (!nextDataLine(in, text, line)) fail(path, "OFF header has no vertex and face counts");
  std::istringstream counts(text);
  if (!(counts >> vertices >> faces)) failAt(path, line, "bad OFF counts '" + text + "'");
  const auto size = std::filesystem::file_size(path);
  if (vertices > size || faces > size)  // a line each
    failAt(path, line, "OFF counts " + std::to_string(vertices) + " and " + std::to_string(faces) +
                           " exceed what a file of " + std::to_string(size) + " bytes holds");
  for (unsigned long long v = 0; v < vertices; ++v) {
    if (!nextDataLine(in, text, line))
      fail(path, "OFF data is cut: " + std::to_string(v) + " of " + std::to_string(vertices) + " vertices");
    std::istringstream words(text);
    checkNumbers(path, line, words, 3, "vertex coordinate");
  }
  for (unsigned long long f = 0; f < faces; ++f) {
    if (!nextDataLine(in, text, line))
      fail(path, "OFF data is cut: " + std::to_string(f) + " of " + std::to_string(faces) + " faces");
    std::istringstream words(text);
    long corners = 0;
    if (!(words >> corners) || corners < 3 || corners > 1024)
      failAt(path, line, "face corner count must be 3..1024");
    for (long k = 0; k < corners; ++k) {
      long long index = -1;
      if (!(words >> index) || index < 0 || (unsigned long long)index >= vertices)
        failAt(path, line, "face corner " + std::to_string(k) + " is not a vertex index below " +
                               std::to_string(vertices));
    }
  }
}

}  // namespace

std::vector<long> PlyCommentLines::all() const {
  std::vector<long> lines;
  std::merge(bare.begin(), bare.end(), info.begin(), info.end(), std::back_inserter(lines));
  return lines;
}

void checkMeshFile(const std::string& path, PlyCommentLines* comments) {
  const std::string ext = lowerExtension(path);
  if (ext == ".obj") checkObjFile(path, nullptr);
  if (ext == ".ply") checkPly(path, comments);
  if (ext == ".off") checkOff(path);
}

namespace {

std::string vertexName(size_t v, const glm::vec3& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "vertex %zu (%g, %g, %g)", v, p.x, p.y, p.z);
  return buf;
}

// Per axis, the 1st and 99th percentile of the coordinates.
std::pair<glm::dvec3, glm::dvec3> bulk(const std::vector<glm::vec3>& positions) {
  glm::dvec3 lo, hi;
  std::vector<float> axis(positions.size());
  const size_t n = axis.size(), a = (n - 1) / 100, b = (n - 1) - (n - 1) / 100;
  for (int k = 0; k < 3; ++k) {
    for (size_t i = 0; i < n; ++i) axis[i] = positions[i][k];
    std::nth_element(axis.begin(), axis.begin() + a, axis.end());
    lo[k] = axis[a];
    std::nth_element(axis.begin(), axis.begin() + b, axis.end());
    hi[k] = axis[b];
  }
  return {lo, hi};
}

}  // namespace

void checkSceneGeometry(const Scene& scene, const std::string& where) {
  if (scene.positions.empty()) return;
  for (size_t v = 0; v < scene.positions.size(); ++v) {
    const glm::vec3& p = scene.positions[v];
    for (int k = 0; k < 3; ++k)
      if (!(std::abs(p[k]) <= kMaxCoordinate))
        fail(where, vertexName(v, p) + ": coordinates must be finite and within 1e15");
  }
  const auto [lo, hi] = bulk(scene.positions);
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  const double reach = kMaxOutlier * (extent > 0.0 ? extent : std::max(1.0, glm::length(lo)));
  for (size_t v = 0; v < scene.positions.size(); ++v) {
    const glm::dvec3 p(scene.positions[v]);
    const glm::dvec3 out = glm::max(lo - p, p - hi);  // > 0 where outside the bulk
    if (std::max({out.x, out.y, out.z}) > reach)
      fail(where, vertexName(v, scene.positions[v]) +
                      " strays more than 1e6 times the extent of the other vertices from them");
  }
  const bool anyArea = std::any_of(scene.triangles.begin(), scene.triangles.end(), [&](const glm::uvec3& t) {
    const glm::dvec3 a(scene.positions[t.x]), b(scene.positions[t.y]), c(scene.positions[t.z]);
    return glm::length(glm::cross(b - a, c - a)) > 0.0;
  });
  if (!scene.triangles.empty() && !anyArea)
    fail(where, "every triangle has zero area (collinear or repeated vertices): nothing to render");
}

}  // namespace mvr
