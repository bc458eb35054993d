#pragma once
// A model read by another process (mvr-import, assimp's formats) as it
// travels back through a pipe: the Scene's geometry and materials, its
// warnings, and the images the file embedded. One JSON header for the
// counts, names and numbers, then the arrays as raw little-endian bytes;
// the reader checks every count and index against what arrived.
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "mvr/scene.h"

namespace mvr {

// An image embedded in the model file: its encoded bytes (PNG, JPEG, ...;
// `hint` the extension) or, where width and height are set, BGRA8 texels.
struct EmbeddedImage {
  std::string hint;
  int width = 0, height = 0;
  std::vector<uint8_t> bytes;
};

struct ImportedModel {
  Scene scene;  // a material's texture "*K" names embedded[K]
  std::vector<EmbeddedImage> embedded;
};

void writeImportedModel(std::ostream& out, const ImportedModel& model);

// Throws mvr::Error naming `where` for bytes that are not a whole, consistent
// model (a count past the end, an index beyond the vertices, a material
// beyond the materials).
ImportedModel readImportedModel(const std::string& bytes, const std::string& where);

}  // namespace mvr
