#include "mvr/lenticular.h"

#include <algorithm>
#include <cmath>

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

glm::ivec2 LenticularMap::texel(int x, int y, int i) const {
  const glm::vec2 uv = panelUv(*this, x, y);
  const int v = view(x, y, i);
  const float su = flipX ? 1.0f - uv.x : uv.x, sv = flipY ? 1.0f - uv.y : uv.y;
  const int col = std::clamp(int(std::floor(su * float(tileW))), 0, tileW - 1);
  const int rowUp = std::clamp(int(std::floor(sv * float(tileH))), 0, tileH - 1);
  return {(v % columns) * tileW + col, quiltHeight - 1 - ((v / columns) * tileH + rowUp)};
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

std::string lenticularGlsl() {
  // The CPU's steps above, one for one; `precise` keeps the compiler from
  // fusing or reordering them.
  return R"(
uniform sampler2D quilt;
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

ivec2 lenticularTexel(vec2 uv, int view) {
  precise float su = flipX ? 1.0 - uv.x : uv.x;
  precise float sv = flipY ? 1.0 - uv.y : uv.y;
  precise float cu = su * float(tileW);
  precise float cv = sv * float(tileH);
  int col = clamp(int(floor(cu)), 0, tileW - 1);
  int rowUp = clamp(int(floor(cv)), 0, tileH - 1);
  return ivec2((view % columns) * tileW + col, quiltHeight - 1 - ((view / columns) * tileH + rowUp));
}

// pixel: x right, y down from the panel's top.
vec3 lenticular(ivec2 pixel) {
  vec2 uv = panelUv(pixel);
  vec3 rgb;
  int channelOf[3] = int[3](ri, 1, bi);
  for (int c = 0; c < 3; ++c) {
    ivec2 t = lenticularTexel(uv, lenticularView(uv, channelOf[c]));
    rgb[c] = texelFetch(quilt, t, 0)[c];  // row 0: the quilt image's top row, as uploaded
  }
  return rgb;
}
)";
}

}  // namespace mvr
