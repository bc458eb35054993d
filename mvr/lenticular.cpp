#include "mvr/lenticular.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "mvr/error.h"
#include "mvr/parallel.h"

namespace mvr {

double PanelCalibration::pitchAcross() const { return pitch * screenW / dpi * std::cos(std::atan(1.0 / slope)); }

LenticularMap LenticularMap::of(const PanelCalibration& panel, const QuiltGrid& grid, int quiltHeight) {
  if (grid.columns < 1 || grid.rows < 1 || grid.views < 1 || grid.views > grid.columns * grid.rows ||
      grid.tileWidth < 1 || grid.tileHeight < 1 || grid.tileHeight * grid.rows > quiltHeight)
    fail("quilt", "its tiles do not fit the quilt");
  LenticularMap m;
  m.screenW = panel.screenW, m.screenH = panel.screenH;
  m.invW = float(1.0 / panel.screenW), m.invH = float(1.0 / panel.screenH);
  m.subp = float(1.0 / (3.0 * panel.screenW));
  m.tilt = float(panel.tilt()), m.pitch = float(panel.pitchAcross()), m.center = float(panel.center);
  m.views = grid.views, m.columns = grid.columns, m.tileW = grid.tileWidth, m.tileH = grid.tileHeight;
  m.quiltHeight = quiltHeight;
  m.invView = panel.invView, m.flipX = panel.flipImageX, m.flipY = panel.flipImageY;
  if (panel.flipSubp) m.ri = 2, m.bi = 0;
  return m;
}

namespace {

// The panel pixel's (u, v): u right, v up, at the pixel's centre.
glm::vec2 panelUv(const LenticularMap& m, int x, int y) {
  const float u = (float(x) + 0.5f) * m.invW;
  const float v = 1.0f - (float(y) + 0.5f) * m.invH;
  return {u, v};
}

float phase(const LenticularMap& m, glm::vec2 uv, int i) {
  const float u = m.flipX ? 1.0f - uv.x : uv.x;
  const float across = u + float(i) * m.subp;
  const float tilted = across + uv.y * m.tilt;
  const float z = tilted * m.pitch - m.center;
  const float f = z - std::floor(z);
  return m.invView ? 1.0f - f : f;
}

}  // namespace

int LenticularMap::view(int x, int y, int i) const {
  const float z = phase(*this, panelUv(*this, x, y), i);
  return std::clamp(int(std::floor(z * float(views))), 0, views - 1);
}

glm::ivec3 LenticularMap::viewTexel(int x, int y, int i) const {
  const glm::vec2 uv = panelUv(*this, x, y);
  const float su = flipX ? 1.0f - uv.x : uv.x, sv = flipY ? 1.0f - uv.y : uv.y;
  const int col = std::clamp(int(std::floor(su * float(tileW))), 0, tileW - 1);
  const int rowUp = std::clamp(int(std::floor(sv * float(tileH))), 0, tileH - 1);
  return {col, tileH - 1 - rowUp, view(x, y, i)};
}

glm::ivec2 LenticularMap::texel(int x, int y, int i) const {
  const glm::ivec3 t = viewTexel(x, y, i);
  return {(t.z % columns) * tileW + t.x, quiltHeight - tileH * (t.z / columns + 1) + t.y};
}

Image nativeImage(const Image& quilt, const LenticularMap& m) {
  if (!isByteType(quilt.type) || quilt.height != m.quiltHeight || quilt.width < m.columns * m.tileW)
    fail("quilt", "does not match the mapping's layout");
  Image out(m.screenW, m.screenH, quilt.type);
  parallelFor(0, m.screenH, [&](int y) {
    for (int x = 0; x < m.screenW; ++x) {
      uint8_t* p = &out.bytes[4 * (size_t(y) * size_t(m.screenW) + size_t(x))];
      const int channelOf[3] = {m.ri, 1, m.bi};  // the subpixel each channel comes from
      for (int c = 0; c < 3; ++c) {
        const glm::ivec2 t = m.texel(x, y, channelOf[c]);
        p[c] = quilt.bytes[4 * (size_t(t.y) * size_t(quilt.width) + size_t(t.x)) + size_t(c)];
      }
      p[3] = 255;
    }
  });
  return out;
}

Image epiVolumeOf(const Image& quilt, const QuiltGrid& g) {
  Image volume(g.tileWidth, g.tileHeight * g.views, quilt.type);
  const size_t pixel = 4 * Image::channelBytes(quilt.type);
  for (int v = 0; v < g.views; ++v) {
    const int top = quilt.height - g.tileHeight * (v / g.columns + 1), left = (v % g.columns) * g.tileWidth;
    for (int s = 0; s < g.tileHeight; ++s)
      std::memcpy(volume.row(s * g.views + v), quilt.row(top + s) + size_t(left) * pixel, volume.rowBytes());
  }
  return volume;
}

std::string lenticularGlsl(ViewLayout layout) {
  // The CPU's steps above, one for one; `precise` keeps the compiler from
  // fusing or reordering them.
  const char* const head = layout == ViewLayout::EpiVolume   ? "#define EPI_VOLUME\nuniform sampler2DArray quilt;\n"
                           : layout == ViewLayout::ViewArray ? "#define VIEW_ARRAY\nuniform sampler2DArray quilt;\n"
                                                             : "uniform sampler2D quilt;\n";
  return std::string(head) +
         R"(
uniform float invW, invH, subp, tilt, pitch, center;
uniform int views, columns, tileW, tileH, quiltHeight, ri, bi;
uniform bool invView, flipX, flipY;

vec2 panelUv(ivec2 p) {
  precise float u = (float(p.x) + 0.5) * invW;
  precise float v = 1.0 - (float(p.y) + 0.5) * invH;
  return vec2(u, v);
}

int lenticularView(vec2 uv, int i) {
  precise float u = flipX ? 1.0 - uv.x : uv.x;
  precise float across = u + float(i) * subp;
  precise float tilted = across + uv.y * tilt;
  precise float z = tilted * pitch - center;
  precise float f = z - floor(z);
  precise float phase = invView ? 1.0 - f : f;
  precise float scaled = phase * float(views);
  return clamp(int(floor(scaled)), 0, views - 1);
}

// The texel's column and row from the bottom within its tile.
ivec2 inTile(vec2 uv) {
  precise float su = flipX ? 1.0 - uv.x : uv.x;
  precise float sv = flipY ? 1.0 - uv.y : uv.y;
  precise float cu = su * float(tileW);
  precise float cv = sv * float(tileH);
  return ivec2(clamp(int(floor(cu)), 0, tileW - 1), clamp(int(floor(cv)), 0, tileH - 1));
}

#if defined(EPI_VOLUME)
// Layer s: the EPI of scanline s (from the top), row v: view v.
vec4 lenticularTexel(ivec2 t, int view) { return texelFetch(quilt, ivec3(t.x, view, tileH - 1 - t.y), 0); }
#elif defined(VIEW_ARRAY)
// Layer v: view v, row 0 its top row.
vec4 lenticularTexel(ivec2 t, int view) { return texelFetch(quilt, ivec3(t.x, tileH - 1 - t.y, view), 0); }
#else
// Row 0: the quilt image's top row, as uploaded.
vec4 lenticularTexel(ivec2 t, int view) {
  return texelFetch(quilt, ivec2((view % columns) * tileW + t.x, quiltHeight - 1 - ((view / columns) * tileH + t.y)), 0);
}
#endif

// pixel: x right, y down from the panel's top. The texel's place in its
// tile is the same for the three subpixels; their views differ.
vec3 lenticular(ivec2 pixel) {
  vec2 uv = panelUv(pixel);
  ivec2 t = inTile(uv);
  return vec3(lenticularTexel(t, lenticularView(uv, ri)).r, lenticularTexel(t, lenticularView(uv, 1)).g,
              lenticularTexel(t, lenticularView(uv, bi)).b);
}
)";
}

}  // namespace mvr
