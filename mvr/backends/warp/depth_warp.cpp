#include "mvr/backends/warp/depth_warp.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <tuple>
#include <vector>

#include <glm/gtc/constants.hpp>

#include "mvr/backends/warp/warp_grid.h"
#include "mvr/error.h"
#include "mvr/gl/gl_program.h"

namespace mvr {
namespace {

// The vertex in reference pixel coordinates (aAt), and the point whose
// pixel gives it depth, label and texture coordinates (aCentre). The grid:
// pixel centres (i + 0.5, j + 0.5), and a ring on the image's border (0
// and W, 0 and H) that takes its pixel's depth, so that warping to the
// reference itself covers every pixel centre (the grid of centres alone
// ends half a pixel short, and fill rules drop centres on its right and
// bottom edges); aAt == aCentre. A splat (below): the corners of a
// silhouette pixel's own footprint, aCentre its centre. Labels and the
// splats are the reference's, made once (WarpReference).
const char* const kWarpVertex = R"(
layout(location = 0) in vec2 aAt;
layout(location = 1) in vec2 aCentre;
layout(binding = 1) uniform sampler2D uDepth;
layout(binding = 2) uniform sampler2D uLabel;
uniform mat4 uPixelToWorld;
uniform mat4 uViewProjection;
// The reference's texture coordinates times its camera z, and that z:
// both linear in the surface point, so a triangle spanning a planar run
// of pixels (GridTriangles) samples the colour exactly, uv = xy / z.
out vec3 vUvZ;
out float vOcc;
out float vDepth;
out vec3 vWorld;
// A sheet's farthest vertex's vDepth: GridTriangles puts it last, the
// provoking vertex under GL's default (last-vertex) convention.
flat out float vFar;

void main() {
  ivec2 size = textureSize(uDepth, 0);
  ivec2 p = clamp(ivec2(floor(aCentre)), ivec2(0), size - 1);
  // Every vertex drawn has a sample (GridTriangles, the splats).
  float z = texelFetch(uDepth, p, 0).r;
  vec4 world = uPixelToWorld * vec4(vec3(aAt, 1.0) * z, 1.0);
  gl_Position = uViewProjection * world;
  vWorld = world.xyz;
  vDepth = gl_Position.w;  // the virtual camera's z
  vFar = vDepth;
  vOcc = texelFetch(uLabel, p, 0).r;
  vUvZ = vec3(aCentre / vec2(size), 1.0) * z;
}
)";

// With SHEET, a rubber sheet's fragment (a triangle across a depth jump):
// a guess at a surface this reference could not see, on the view's ray
// behind the sheet's point, no farther than the jump's far side. The other
// reference sees that stretch of the ray as a segment of its image; if at
// every pixel of it that reference sees nothing, or a surface beyond the
// ray's point there, the stretch is empty (a surface on it would show, or
// hide what shows) and the fragment is dropped.
const char* const kWarpFragment = R"(
layout(binding = 0) uniform sampler2D uColor;
in vec3 vUvZ;
in float vOcc;
in float vDepth;
in vec3 vWorld;
flat in float vFar;
// rgb, and the virtual camera's z, negative where labelled occluded: one
// target to write (a CPU GL pays per target and fragment).
layout(location = 0) out vec4 oColor;

#ifdef SHEET
layout(binding = 4) uniform sampler2D uOtherDepth;  // the other reference's camera z
uniform mat4 uOtherWorldToPixel;                    // world to its (x z, y z, z)
uniform vec3 uEye;                                  // the view's
uniform float uTau;

bool seenThrough() {
  // The ray's points from here to the far side, in the other reference's
  // (x z, y z, z): near + s (far - near), s in [0, 1], linear in world.
  vec3 near = (uOtherWorldToPixel * vec4(vWorld, 1.0)).xyz;
  vec3 far = (uOtherWorldToPixel * vec4(uEye + (vWorld - uEye) * max(vFar / vDepth, 1.0), 1.0)).xyz;
  if (!(near.z > 0.0) || !(far.z > 0.0)) return false;
  vec2 from = near.xy / near.z, to = far.xy / far.z;
  int axis = abs(to.x - from.x) >= abs(to.y - from.y) ? 0 : 1;
  ivec2 size = textureSize(uOtherDepth, 0);
  int steps = int(min(ceil(abs(to[axis] - from[axis])), float(size.x + size.y)));
  vec3 d = far - near;
  for (int k = 0; k <= steps; ++k) {
    // The ray's point whose pixel coordinate along the axis is u.
    float u = mix(from[axis], to[axis], steps > 0 ? float(k) / float(steps) : 0.0);
    float s = abs(d[axis] - u * d.z) > 1e-20 ? clamp((u * near.z - near[axis]) / (d[axis] - u * d.z), 0.0, 1.0) : 0.0;
    vec3 p = near + s * d;
    vec2 at = floor(p.xy / p.z);
    if (any(lessThan(at, vec2(0.0))) || any(greaterThanEqual(at, vec2(size)))) return false;
    float seen = texelFetch(uOtherDepth, ivec2(at), 0).r;
    if (seen > 0.0 && seen < p.z * (1.0 + uTau)) return false;
  }
  return true;
}
#endif

void main() {
#ifdef SHEET
  if (seenThrough()) discard;
#endif
  oColor = vec4(texture(uColor, vUvZ.xy / vUvZ.z).rgb, vOcc > 0.5 ? -vDepth : vDepth);
}
)";

// The composite's full-screen triangle.
const char* const kCoverageVertex = R"(
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

// Where reference 0 drew: both references blended, or reference 0 alone.
// With REST, where reference 1 drew and 0 did not. A reference drew where
// its depth buffer (cleared to 0, far in reversed Z) is above 0: read as a
// texture, not tested as the pass's depth attachment. Tested, it was a
// depth buffer the warp had just drawn into through another framebuffer,
// and NVIDIA's driver culled whole tiles of it that were drawn (on an
// H200, the fourth view of a synthesize lost the top of the cup). The
// warped colours are not cleared between views: coverage decides what is
// read.
// The weight of reference 0 (depth_warp.h; keep in step with warpWeight).
const char* const kComposite = R"(
layout(binding = 0) uniform sampler2D uWarped0;  // rgb, signed z (kWarpFragment)
layout(binding = 1) uniform sampler2D uCover0;   // depth buffer: > 0 where drawn
layout(binding = 2) uniform sampler2D uWarped1;
layout(binding = 3) uniform sampler2D uCover1;
uniform int uTwo;
uniform mat4 uPixelToWorld;
uniform vec3 uCenter;
uniform vec3 uCenter0;
uniform vec3 uCenter1;
uniform float uTau;
uniform float uA;
layout(location = 0) out vec4 oColor;

float angle(vec3 p, vec3 a, vec3 b) {
  return acos(clamp(dot(normalize(a - p), normalize(b - p)), -1.0, 1.0));
}

float weight0(float theta0, float theta1, float z0, float z1, float occ0, float occ1) {
  float s = theta0 + theta1 > 0.0 ? theta0 / (theta0 + theta1) : 0.5;
  float wAng = 0.5 + 0.5 * cos(3.14159265358979 * s);
  float closer0 = z0 - z1 < -uTau * z0 ? 1.0 : 0.0;
  float closer1 = z1 - z0 < -uTau * z1 ? 1.0 : 0.0;
  float phi0 = min(1.0, occ0 * pow(uA * s, 4.0));
  float phi1 = min(1.0, occ1 * pow(uA * (1.0 - s), 4.0));
  float w = min(1.0, phi1 + (1.0 - phi0) * clamp(wAng + phi0 * closer0 - phi1 * closer1, 0.0, 1.0));
  return clamp(w, 0.0, 1.0);
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  bool drew0 = texelFetch(uCover0, px, 0).r > 0.0;
#ifdef REST
  if (drew0 || !(texelFetch(uCover1, px, 0).r > 0.0)) discard;
  oColor = vec4(texelFetch(uWarped1, px, 0).rgb, 1.0);
#else
  if (!drew0) discard;
  vec4 c0 = texelFetch(uWarped0, px, 0);
  if (uTwo == 0 || !(texelFetch(uCover1, px, 0).r > 0.0)) { oColor = vec4(c0.rgb, 1.0); return; }
  vec4 c1 = texelFetch(uWarped1, px, 0);
  float z0 = abs(c0.a), z1 = abs(c1.a);
  vec3 p = (uPixelToWorld * vec4(vec3(gl_FragCoord.xy, 1.0) * min(z0, z1), 1.0)).xyz;
  float occ0 = c0.a < 0.0 ? 1.0 : 0.0, occ1 = c1.a < 0.0 ? 1.0 : 0.0;
  float w = weight0(angle(p, uCenter, uCenter0), angle(p, uCenter, uCenter1), z0, z1, occ0, occ1);
  oColor = vec4(w * c0.rgb + (1.0 - w) * c1.rgb, 1.0);
#endif
}
)";

void setMatrix(const gl::Program& p, const char* name, const glm::dmat4& m) { gl::setUniform(p, name, glm::mat4(m)); }

}  // namespace

float warpWeight(float theta0, float theta1, float z0, float z1, float occ0, float occ1, float tau, float a) {
  const float s = theta0 + theta1 > 0.0f ? theta0 / (theta0 + theta1) : 0.5f;
  return compositeWeight(s, std::cos(glm::pi<float>() * s), z0, z1, occ0, occ1, tau, a);
}

std::pair<int, int> nearestPair(const std::vector<glm::dvec3>& centres, const glm::dvec3& eye) {
  auto distance = [&](int k) { return glm::length(centres[size_t(k)] - eye); };
  int a = 0;
  for (int k = 1; k < int(centres.size()); ++k)
    if (distance(k) < distance(a)) a = k;
  const glm::dvec3 ca = centres[size_t(a)], toEye = eye - ca;
  if (glm::length(toEye) <= 1e-9 * (1.0 + glm::length(ca))) return {a, -1};
  int b = -1;
  for (int k = 0; k < int(centres.size()); ++k)
    if (k != a && glm::dot(centres[size_t(k)] - ca, toEye) > 0.0 && (b < 0 || distance(k) < distance(b))) b = k;
  return {a, b};
}

WarpReference WarpReference::upload(const RgbdView& view, float tau, float flatness, double baseline) {
  const int w = view.color.width, h = view.color.height;
  if (view.color.type != PixelType::F32) fail("RGB-D reference", "colour must be float");
  if (view.depth.width != w || view.depth.height != h)
    fail("RGB-D reference", "depth is " + std::to_string(view.depth.width) + "x" +
                                std::to_string(view.depth.height) + ", colour " + std::to_string(w) + "x" +
                                std::to_string(h));
  WarpReference r;
  r.width = w, r.height = h;
  r.color = gl::Texture::image2D(GL_RGBA32F, w, h, GL_LINEAR);
  gl::TextureSubImage2D(r.color.id(), 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, view.color.bytes.data());
  r.depth = gl::Texture::image2D(GL_R32F, w, h, GL_NEAREST);
  gl::TextureSubImage2D(r.depth.id(), 0, 0, 0, w, h, GL_RED, GL_FLOAT, view.depth.values.data());
  std::vector<float> labels;
  std::vector<uint32_t> silhouettes;
  labelPixels(view.depth, tau, labels, silhouettes);
  r.label = gl::Texture::image2D(GL_R32F, w, h, GL_NEAREST);
  gl::TextureSubImage2D(r.label.id(), 0, 0, 0, w, h, GL_RED, GL_FLOAT, labels.data());
  const Splats splats = makeSplats(silhouettes, w);
  r.splatVertices = gl::makeBuffer(splats.vertices.data(), splats.vertices.size());
  r.splatIndices = gl::makeBuffer(splats.indices.data(), splats.indices.size());
  r.splatIndexCount = splats.indices.size();
  const double focal = std::max(std::abs(view.K[0][0]), std::abs(view.K[1][1]));
  const float deviation = flatness > 0.0f && focal * baseline > 0.0 ? float(flatness / (focal * baseline)) : 0.0f;
  const auto [triangles, sheets] = gridTriangles(view.depth, labels, tau, deviation);
  r.triangles = gl::makeBuffer(triangles.data(), triangles.size());
  r.triangleIndexCount = triangles.size();
  r.sheetIndexStart = sheets;
  r.pixelToWorld = glm::mat4(RgbdView::pixelToWorld(view.K, view.V));
  r.center = glm::vec3(view.center());
  gl::checkError("uploading an RGB-D reference");
  return r;
}

DepthWarp::DepthWarp(float tau, float a)
    : warp_(gl::linkProgram("warp", {{GL_VERTEX_SHADER, gl::glslHeader() + kWarpVertex},
                                     {GL_FRAGMENT_SHADER, gl::glslHeader() + kWarpFragment}})),
      warpSheet_(gl::linkProgram("warp-sheet", {{GL_VERTEX_SHADER, gl::glslHeader() + kWarpVertex},
                                                {GL_FRAGMENT_SHADER, gl::glslHeader({"SHEET"}) + kWarpFragment}})),
      composite_(gl::linkProgram("warp-composite", {{GL_VERTEX_SHADER, gl::glslHeader() + kCoverageVertex},
                                                    {GL_FRAGMENT_SHADER, gl::glslHeader() + kComposite}})),
      compositeRest_(gl::linkProgram("warp-composite-rest",
                                     {{GL_VERTEX_SHADER, gl::glslHeader() + kCoverageVertex},
                                      {GL_FRAGMENT_SHADER, gl::glslHeader({"REST"}) + kComposite}})),
      grid_(gl::VertexArray::create()),
      splats_(gl::VertexArray::create()),
      empty_(gl::VertexArray::create()),
      over_(gl::Framebuffer::create()) {
  // A splat vertex (makeSplats): corner, then centre.
  for (GLuint attribute : {0u, 1u}) {
    splats_.attribute(attribute, 2, attribute * sizeof(glm::vec2));
  }
  gl::setUniform(composite_, "uTau", tau);
  gl::setUniform(warpSheet_, "uTau", tau);
  gl::setUniform(composite_, "uA", a);
}

// The static grid (seed 5.2): one vertex per reference pixel centre and
// the border ring, (W + 2) x (H + 2), made once per reference size; each
// reference brings its own list of triangles (GridTriangles).
void DepthWarp::ensureGrid(int w, int h) {
  if (w == gridWidth_ && h == gridHeight_) return;
  auto at = [](int k, int n) { return std::clamp(float(k) - 0.5f, 0.0f, float(n)); };
  const int gw = w + 2, gh = h + 2;
  std::vector<glm::vec2> vertices;
  vertices.reserve(size_t(gw) * gh);
  for (int j = 0; j < gh; ++j)
    for (int i = 0; i < gw; ++i) vertices.emplace_back(at(i, w), at(j, h));
  gridVertices_ = gl::makeBuffer(vertices.data(), vertices.size());
  // A grid vertex is its own centre: both attributes read the same vec2.
  grid_.vertexBuffer(gridVertices_.id(), sizeof(glm::vec2));
  for (GLuint attribute : {0u, 1u}) {
    grid_.attribute(attribute, 2, 0);
  }
  gridWidth_ = w, gridHeight_ = h;
}

void DepthWarp::ensureTargets(int w, int h) {
  for (Warped& t : warped_) {
    if (t.width == w && t.height == h) continue;
    t.width = w, t.height = h;
    t.color = gl::Texture::image2D(GL_RGBA32F, w, h, GL_NEAREST);
    t.zbuffer = gl::Texture::image2D(GL_DEPTH_COMPONENT32F, w, h, GL_NEAREST);
    t.fbo = gl::Framebuffer::create();
    t.fbo.attach(GL_COLOR_ATTACHMENT0, t.color.id(), 0);
    t.fbo.attach(GL_DEPTH_ATTACHMENT, t.zbuffer.id(), 0);
    if (!t.fbo.complete())
      fail("GL", "warp target is incomplete");
  }
}

void DepthWarp::warp(const WarpReference& ref, const WarpReference* other, const WarpCamera& view, const Warped& into,
                     bool clearColor) const {
  into.fbo.bind();
  gl::Viewport(0, 0, into.width, into.height);
  const float zero[4] = {0, 0, 0, 0};
  if (clearColor) gl::ClearNamedFramebufferfv(into.fbo.id(), GL_COLOR, 0, zero);
  gl::ClearNamedFramebufferfi(into.fbo.id(), GL_DEPTH_STENCIL, 0, 0.0f, 0);
  ref.color.bind(0);
  ref.depth.bind(1);
  ref.label.bind(2);
  for (const gl::Program* p : {&warp_, &warpSheet_}) {
    gl::setUniform(*p, "uPixelToWorld", ref.pixelToWorld);
    setMatrix(*p, "uViewProjection", view.viewProjection);
  }
  grid_.bind();
  grid_.elementBuffer(ref.triangles.id());
  // The surfaces, then the rubber sheets, tested against the other
  // reference where there is one.
  warp_.use();
  const size_t sheets = other ? ref.sheetIndexStart : ref.triangleIndexCount;
  if (sheets) gl::DrawElements(GL_TRIANGLES, GLsizei(sheets), GL_UNSIGNED_INT, nullptr);
  if (sheets < ref.triangleIndexCount) {
    warpSheet_.use();
    other->depth.bind(4);
    gl::setUniform(warpSheet_, "uOtherWorldToPixel", glm::inverse(other->pixelToWorld));
    gl::setUniform(warpSheet_, "uEye", glm::vec3(view.center));
    gl::DrawElements(GL_TRIANGLES, GLsizei(ref.triangleIndexCount - sheets), GL_UNSIGNED_INT,
                     reinterpret_cast<const void*>(sheets * sizeof(uint32_t)));
    warp_.use();
  }
  if (!ref.splatIndexCount) return;
  splats_.bind();
  splats_.vertexBuffer(ref.splatVertices.id(), sizeof(glm::vec4));
  splats_.elementBuffer(ref.splatIndices.id());
  gl::DrawElements(GL_TRIANGLES, GLsizei(ref.splatIndexCount), GL_UNSIGNED_INT, nullptr);
}

DepthWarp::WarpedImage DepthWarp::read(const Warped& from) const {
  WarpedImage out{Image(from.width, from.height, PixelType::F32), DepthImage(from.width, from.height)};
  gl::GetTextureSubImage(from.color.id(), 0, 0, 0, 0, from.width, from.height, 1, GL_RGBA, GL_FLOAT,
                         GLsizei(out.color.bytes.size()), out.color.bytes.data());
  // Alpha holds the signed depth (kWarpFragment): split it into the label
  // and the depth image.
  float* rgba = reinterpret_cast<float*>(out.color.bytes.data());
  for (size_t k = 0; k < out.depth.values.size(); ++k) {
    float& a = rgba[4 * k + 3];
    out.depth.values[k] = std::abs(a);
    a = a < 0.0f ? 1.0f : 0.0f;
  }
  return out;
}

DepthWarp::WarpedImage DepthWarp::warped(const WarpReference& ref, const WarpCamera& view, int width, int height) {
  ensureGrid(ref.width, ref.height);
  ensureTargets(width, height);
  setDepthConvention();
  warp(ref, nullptr, view, warped_[0], true);
  return read(warped_[0]);
}

long DepthWarp::holes(const WarpReference& a, const WarpReference& b, const WarpCamera& view, int width,
                      int height) {
  const WarpedImage w0 = warped(a, view, width, height), w1 = warped(b, view, width, height);
  const float* c0 = reinterpret_cast<const float*>(w0.color.bytes.data());
  const float* c1 = reinterpret_cast<const float*>(w1.color.bytes.data());
  long count = 0;
  for (size_t i = 0; i < w0.depth.values.size(); ++i) {
    const bool seen0 = w0.depth.values[i] > 0.0f, seen1 = w1.depth.values[i] > 0.0f;
    const bool sheet0 = !seen0 || c0[4 * i + 3] > 0.5f, sheet1 = !seen1 || c1[4 * i + 3] > 0.5f;
    count += (seen0 || seen1) && sheet0 && sheet1;
  }
  return count;
}

void DepthWarp::render(const WarpReference& a, const WarpReference* b, const WarpCamera& view,
                       const RenderTarget& target) {
  if (b && (b->width != a.width || b->height != a.height))
    fail("RGB-D references", "two references of different sizes");
  ensureGrid(a.width, a.height);
  ensureTargets(target.width(), target.height());
  setDepthConvention();
  warp(a, b, view, warped_[0], false);
  if (b) warp(*b, &a, view, warped_[1], false);
  target.bind();
  target.clear();
  composite_.use();
  gl::setUniform(composite_, "uTwo", b ? 1 : 0);
  setMatrix(composite_, "uPixelToWorld", view.pixelToWorld);
  gl::setUniform(composite_, "uCenter", glm::vec3(view.center));
  gl::setUniform(composite_, "uCenter0", a.center);
  gl::setUniform(composite_, "uCenter1", b ? b->center : a.center);
  warped_[0].color.bind(0);
  warped_[0].zbuffer.bind(1);
  warped_[1].color.bind(2);
  warped_[1].zbuffer.bind(3);
  empty_.bind();
  // The target's colour alone, so no depth test (kComposite).
  over_.bind();
  over_.attach(GL_COLOR_ATTACHMENT0, target.colorTexture(), 0);
  for (int k = 0; k < (b ? 2 : 1); ++k) {
    (k == 0 ? composite_ : compositeRest_).use();
    gl::DrawArrays(GL_TRIANGLES, 0, 3);
  }
  over_.attach(GL_COLOR_ATTACHMENT0, 0, 0);
  target.bind();
  gl::checkError("depth warp");
}

void labelPixels(const DepthImage& d, float tau, std::vector<float>& labels, std::vector<uint32_t>& silhouettes) {
  const int w = d.width, h = d.height;
  labels.assign(size_t(w) * h, 0.0f);
  auto inside = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float z = d.at(x, y);
      bool jump = false, edge = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if ((dx == 0 && dy == 0) || !inside(x + dx, y + dy)) continue;
          const float n = d.at(x + dx, y + dy);
          const bool empty = !(n > 0.0f);
          edge = edge || empty;
          if (dx == 0 || dy == 0) jump = jump || empty || !oneSurface(n, z, tau);
        }
      labels[size_t(y) * w + x] = jump ? 1.0f : 0.0f;
      if (z > 0.0f && edge) silhouettes.push_back(uint32_t(y * w + x));
    }
}

}  // namespace mvr
