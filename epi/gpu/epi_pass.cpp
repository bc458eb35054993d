#include "epi/gpu/epi_pass.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "epi/gpu/pst_geometry.h"
#include "mvr/error.h"
#include "mvr/gl/gl_program.h"
#include "shading/lighting.h"
#include "shading/texture_vector.h"
#include "shading/view_dependent.h"

namespace mvr {
namespace {

// What the vertex stage hands the fragment shaders, whether it reads
// CPU-built vertices or pulls them from the GPU slice table.
const char* const kSliverOutputs = R"(
uniform vec2 uScale;
invariant gl_Position;
noperspective out float vView;
flat out vec4 vFlat;
noperspective out vec4 vA[NV];
#ifdef VECTOR
flat out int vVectorBase;
#endif
)";

const char* const kExactOutputs = R"(
uniform vec2 uScale;
invariant gl_Position;
flat out vec4 vEnds;
flat out vec4 vFlat;
flat out vec4 vA0[NV];
flat out vec4 vA1[NV];
#ifdef VECTOR
flat out int vVectorBase;
#endif
flat out vec4 vEndX;      // x0, dx of both ends
flat out float vRowBase;  // target row of r = 0
)";

const char* const kSliverVertex = R"(
layout(location = 0) in vec4 aPos;    // x, stacked row, depth, view
layout(location = 1) in vec4 aFlat;   // side, material
layout(location = 2) in vec4 aA[NV];
void main() {
  gl_Position = vec4(aPos.xy * uScale - 1.0, aPos.z, 1.0);
  vView = aPos.w;
  vFlat = aFlat;
  for (int i = 0; i < NV; ++i) vA[i] = aA[i];
#ifdef VECTOR
  vVectorBase = int(round(aA[0].z));
#endif
}
)";

const char* const kSliverFragment = R"(
noperspective in float vView;
flat in vec4 vFlat;
noperspective in vec4 vA[NV];
float gView;
void prepare() { gView = vView; }
float attr(int i) { return vA[i >> 2][i & 3]; }
)";

const char* const kExactVertex = R"(
layout(location = 0) in vec4 aPos;    // x, stacked row, stacked row of r = 0
layout(location = 1) in vec4 aEnds;   // depth0, depth1, 1/w0, 1/w1
layout(location = 2) in vec4 aFlat;   // side, material
layout(location = 3) in vec4 aEndX;   // x0, dx of both ends
layout(location = 4) in vec4 aA0[NV];
layout(location = 4 + NV) in vec4 aA1[NV];
void main() {
  gl_Position = vec4(aPos.xy * uScale - 1.0, aEnds.x, 1.0);
  vEndX = aEndX;
  vRowBase = aPos.z;
  vEnds = aEnds;
  vFlat = aFlat;
  for (int i = 0; i < NV; ++i) { vA0[i] = aA0[i]; vA1[i] = aA1[i]; }
#ifdef VECTOR
  vVectorBase = int(round(aA0[0].y));
#endif
}
)";

// Solves the slice parameter u of the pixel exactly, then interpolates
// hyperbolically; depth is linear in u and written here. The pixel's view
// and u come from its centre and the ends' tracks, not from interpolated
// varyings: GLs interpolate with errors of their own that grow with a
// PST's extent (an NVIDIA H100 over long tracks: issue 21).
const char* const kExactFragment = R"(
flat in vec4 vEnds;
flat in vec4 vFlat;
flat in vec4 vA0[NV];
flat in vec4 vA1[NV];
flat in vec4 vEndX;
flat in float vRowBase;
float gU, gInvW, gView;
vec2 gNumDen;  // x - x0(r), x1(r) - x0(r)
void prepare() {
  float r = gl_FragCoord.y - vRowBase;
  // Each end its own edge's value (as the CPU's rowSpan): slices sharing
  // an edge test a centre on it against the same value.
  float x0 = vEndX.x + (r - 0.5) * vEndX.y, x1 = vEndX.z + (r - 0.5) * vEndX.w;
  gView = r - 0.5;
  gNumDen = vec2(gl_FragCoord.x - x0, x1 - x0);
  // The exact span, as the CPU's: centres in [min, max) of the two ends.
  // (A slice of no width keeps no centre, so the division below is safe.)
  if (!(gl_FragCoord.x >= min(x0, x1) && gl_FragCoord.x < max(x0, x1))) discard;
  gU = clamp(gNumDen.x / gNumDen.y, 0.0, 1.0);
  gInvW = mix(vEnds.z, vEnds.w, gU);
  // Later passes test depth EQUAL against the first's: every program must
  // round this alike, so no contraction into fused multiply-adds.
  precise float depth = mix(vEnds.x, vEnds.y, gU);
  gl_FragDepth = depth;
}
float attr(int i) { return mix(vA0[i >> 2][i & 3], vA1[i >> 2][i & 3], gU) / gInvW; }
)";

// The same outputs as kSliverVertex and kExactVertex, from vertices pulled
// out of the GPU slice table (epi/gpu/pst_geometry.h) instead of vertex
// attributes; passAttribute() (per pass) reads an endpoint's attribute i.
const char* const kPulledSliverHead = R"(
PstVertex pullSliverVertex() {
  PstVertex p = pullPstVertex();
  float depth = p.e0.depth + (p.e1.depth - p.e0.depth) * p.u;
  gl_Position = vec4(vec2(p.x, p.y) * uScale - 1.0, depth, 1.0);
  vView = p.r - 0.5;
  vFlat = vec4(p.front ? 1.0 : -1.0, p.material, 0.0, 0.0);
  return p;
}
)";

const char* const kPulledExactHead = R"(
uniform float uEdgeSnap;  // EpiPass::edgeSnap()
PstVertex pullExactVertex() {
  PstVertex p = pullPstVertex();
  // Widened outward (end 0 at u = 0, end 1 at u = 1; x1 > x0 on a front
  // piece) so that snapping cannot lose a pixel the exact span covers.
  float margin = uEdgeSnap * (1.0 + max(abs(p.e0.dx), abs(p.e1.dx)));
  float x = p.x + (2.0 * p.u - 1.0) * (p.front ? margin : -margin);
  gl_Position = vec4(vec2(x, p.y) * uScale - 1.0, p.e0.depth, 1.0);
  vEndX = vec4(p.e0.x0, p.e0.dx, p.e1.x0, p.e1.dx);
  vRowBase = p.y - p.r;
  vEnds = vec4(p.e0.depth, p.e1.depth, p.e0.invW, p.e1.invW);
  vFlat = vec4(p.front ? 1.0 : -1.0, p.material, 0.0, 0.0);
  return p;
}
)";

const char* const kPulledSliverVertex = R"(
void main() {
  PstVertex p = pullSliverVertex();
  float invW = p.e0.invW + (p.e1.invW - p.e0.invW) * p.u;
  for (int c = 0; c < NV; ++c) vA[c] = vec4(0.0);
  for (int i = 0; i < NA; ++i) {
    float a0 = passAttribute(p.e0, i, p.front), a1 = passAttribute(p.e1, i, p.front);
    vA[i >> 2][i & 3] = (a0 + (a1 - a0) * p.u) / invW;
  }
}
)";

const char* const kPulledExactVertex = R"(
void main() {
  PstVertex p = pullExactVertex();
  for (int c = 0; c < NV; ++c) vA0[c] = vA1[c] = vec4(0.0);
  for (int i = 0; i < NA; ++i) {
    vA0[i >> 2][i & 3] = passAttribute(p.e0, i, p.front);
    vA1[i >> 2][i & 3] = passAttribute(p.e1, i, p.front);
  }
}
)";

// Slices coloured by texture vectors (their own, or the scene's extracted
// per batch): the attributes of EpiPass::linear(), u running from u0 at
// end 0 to u1 at end 1, the first texel an exact integer.
const char* const kPulledVectorSliverVertex = R"(
void main() {
  PstVertex p = pullSliverVertex();
  uvec4 vector = sliceVector(p);
  float u0 = uintBitsToFloat(vector.z), u1 = uintBitsToFloat(vector.w);
  float width = widthAt(p.e0, p.e1, p.r);
  for (int c = 0; c < NV; ++c) vA[c] = vec4(0.0);
  vA[0] = vec4((u0 + (u1 - u0) * p.u) * width, width, 0.0, float(vector.y));
  vVectorBase = int(vector.x);
}
)";

const char* const kPulledVectorExactVertex = R"(
void main() {
  PstVertex p = pullExactVertex();
  uvec4 vector = sliceVector(p);
  for (int c = 0; c < NV; ++c) vA0[c] = vA1[c] = vec4(0.0);
  vA0[0] = vec4(uintBitsToFloat(vector.z), 0.0, float(vector.y), 0.0);
  vA1[0] = vec4(uintBitsToFloat(vector.w), 0.0, float(vector.y), 0.0);
  vVectorBase = int(vector.x);
}
)";

// Where a pass's attributes lie in the endpoint records (the order
// EpiPass::gather copies them in).
std::string passAttributeGlsl(shading::Pass pass, const shading::ShadingPlan& plan) {
  const int head = GpuVertices::kRecordHead;
  std::string body;
  switch (pass) {
    case shading::Pass::Diffuse: body = "endAttribute(e, (front ? 4 : 7) + i)"; break;
    case shading::Pass::Texture: body = "endAttribute(e, " + std::to_string(head + plan.uv) + " + i)"; break;
    case shading::Pass::ViewDependent:  // position, normal, albedo, reflection: one run (ShadingPlan)
      body = "endAttribute(e, " + std::to_string(head + plan.position) + " + i)";
      break;
  }
  return "float passAttribute(End e, int i, bool front) { return " + body + "; }\n";
}

const char* const kAttributeHelpers = R"(
vec2 attr2(int i) { return vec2(attr(i), attr(i + 1)); }
vec3 attr3(int i) { return vec3(attr(i), attr(i + 1), attr(i + 2)); }
layout(location = 0) out vec4 oColor;
)";

// Direct: uv divided per pixel; the level of detail from the horizontal
// footprint only (an EPI has no scanline neighbour; see BENCHMARKS.md).
const char* const kTextureDirectMain = R"(
void main() {
  prepare();
  vec2 uv = attr2(0);
#ifdef EXACT
  // Analytic: dFdx would see u clamped at the slice's ends.
  vec2 a = vec2(vA0[0].x, vA0[0].y), b = vec2(vA1[0].x, vA1[0].y);
  vec2 duv = (b * vEnds.z - a * vEnds.w) / (gInvW * gInvW) / gNumDen.y;
#else
  vec2 duv = dFdx(uv);
#endif
  // The footprint taken as round: the vertical gradient is the horizontal
  // one turned a quarter. Passing it twice makes a degenerate, needle-like
  // footprint that GLs may filter anisotropically (NVIDIA sampled too
  // sharp a level: 34 dB against svr and the CPU spans' 44).
  oColor = materialTexel(int(vFlat.y), uv, duv, vec2(-duv.y, duv.x));
#ifdef EMISSION_TEXTURE
  finishTexel(materialGlow(int(vFlat.y), uv, duv, vec2(-duv.y, duv.x)));
#else
  finishTexel(vec3(0.0));
#endif
}
)";

// Vector: the parameter u, first texel and length. Exact mode has u from
// the slice parameter; the sliver modes divide u times the slice's width
// by the width (both affine in x and r) so that u is exact there too.
const char* const kTextureVectorMain = R"(
layout(binding = 3) uniform samplerBuffer uVectorTexels;
flat in int vVectorBase;
void main() {
  prepare();
  int base = vVectorBase;
#ifdef EXACT
  float u = mix(vA0[0].x, vA1[0].x, gU), k = vA0[0].z;
  float perPixel = k * abs(vA1[0].x - vA0[0].x) / abs(gNumDen.y);  // du/dx
#else
  float u = vA[0].y == 0.0 ? 0.0 : vA[0].x / vA[0].y, k = round(vA[0].w);
  float perPixel = abs(dFdx(u)) * k;
#endif
  oColor = k == 0.0 ? vec4(1.0) : sampleTextureVector(uVectorTexels, base, k, u, perPixel);
  vec3 glow = vec3(0.0);
#ifdef EMISSION_TEXTURE
  // The emission texture's vector follows the base texture's chain.
  if (k != 0.0 && hasEmissionTexture(int(vFlat.y)))
    glow = materialEmission(int(vFlat.y)) *
           sampleTextureVector(uVectorTexels, base + int(2.0 * k) - 1, k, u, perPixel).rgb;
#endif
#ifdef HIGHLIGHTS
  // Split track: the highlight at two knots (rgb, row), linear between.
#ifdef EXACT
  vec4 a = vA0[1], b = vA0[2];
#else
  vec4 a = vA[1], b = vA[2];
#endif
  float t = b.w > a.w ? clamp((gView + 0.5 - a.w) / (b.w - a.w), 0.0, 1.0) : 0.0;
  oColor.rgb += mix(a.rgb, b.rgb, t);
#endif
  finishTexel(glow);
}
)";

// What the texture pass does with its texel T (in oColor) and the
// emission G of its emission texture. The cut-outs' depth pass drops the
// cut texels. The texture pass multiplies the lit colour, which carries
// the material's emission E unless E has a texture; with EMISSION it
// blends by two sources, colour = colour * T + E (1 - T), so that the
// emission comes through undimmed, or colour * T + G.
const char* const kFinishTexel = R"(
#if defined(MASK_DEPTH)
void finishTexel(vec3 glow) {
  if (maskedOut(int(vFlat.y), oColor.a)) discard;
}
#elif defined(EMISSION)
layout(location = 0, index = 1) out vec4 oFactor;
void finishTexel(vec3 glow) {
  oFactor = oColor;
  int material = int(vFlat.y);
  oColor = vec4(hasEmissionTexture(material) ? glow : materialEmission(material) * (1.0 - oColor.rgb), 0.0);
}
#else
void finishTexel(vec3 glow) {}
#endif
)";

const char* const kDiffuseMain = R"(
void main() {
  prepare();
  oColor = vec4(attr3(0), 1.0);
}
)";

// Attributes: position (3), normal (3), with GGX the diffuse albedo (3),
// then, with REFLECT, the reflection vector's affine form A (3), M (6):
// R(eye) = A + M eye. GGX takes off the diffuse light its Fresnel term
// reflects (before the texture pass's multiply had it: untextured albedo).
const char* const kViewDependentMain = R"(
uniform vec3 uEye0;     // eye of view 0 of this row
uniform vec3 uEyeStep;  // eye movement per view
void main() {
  prepare();
  vec3 eye = uEye0 + gView * uEyeStep;
  int material = int(vFlat.y);
#ifdef GGX
  vec3 albedo = attr3(6);
  const int kReflect = 9;
#else
  vec3 albedo = vec3(0.0);
  const int kReflect = 6;
#endif
  vec3 c, loss;
  viewDependentLight(material, albedo, attr3(0), attr3(3) * vFlat.x, eye, c, loss);
  c -= loss;
#ifdef REFLECT
  c += environmentLight(material, reflectionVector(attr3(kReflect), attr3(kReflect + 3), attr3(kReflect + 6), eye));
#endif
  oColor = vec4(c, 1.0);
}
)";

int passAttributeCount(shading::Pass pass, const EpiShading& shading) {
  const shading::ShadingPlan& plan = shading.plan;
  switch (pass) {
    case shading::Pass::Diffuse: return 3;
    case shading::Pass::Texture:
      if (shading.sliceHighlights) return 12;  // + highlight and row at two knots
      return shading.textureMode == TextureMode::Vector || shading.sliceVectors ? 4 : 2;
    case shading::Pass::ViewDependent: return 6 + (plan.albedo >= 0 ? 3 : 0) + (plan.reflect >= 0 ? 9 : 0);
  }
  return 0;
}

}  // namespace

EpiPass::EpiPass(PstMode mode, shading::Pass pass, const EpiShading& shading, bool pulled, bool maskDepth)
    : mode_(mode), pass_(pass), shading_(shading), maskDepth_(maskDepth), count_(passAttributeCount(pass, shading)) {
  if (maskDepth && (pass != shading::Pass::Texture || shading.sliceVectors || !shading.plan.mask))
    fail("EpiPass", "a cut-out depth pass is the texture pass of a scene with cut-outs");
  if (pulled && linear() && shading.sliceHighlights)
    fail("EpiPass", "split highlight tracks are not pulled");
  if (shading.sliceVectors && pass != shading::Pass::Texture)
    fail("EpiPass", "slices coloured by vectors take the texture pass only");
  if (pass != shading::Pass::Diffuse && !shading.scene && !shading.sliceVectors)
    fail("EpiPass", std::string(shading::passName(pass)) + " pass needs a scene");
  if (pass == shading::Pass::Texture && !shading.textures && !shading.sliceVectors)
    fail("EpiPass", "texture pass needs the scene's textures");
  const bool exact = mode == PstMode::Exact;
  std::string header = gl::glslHeader({"NV " + std::to_string(chunks())});
  if (exact) header += "#define EXACT\n";
  if (pass == shading::Pass::ViewDependent && shading.plan.reflect >= 0) header += "#define REFLECT\n";
  if (pass == shading::Pass::Texture && shading.sliceHighlights) header += "#define HIGHLIGHTS\n";
  if (linear()) header += "#define VECTOR\n";
  if (emission()) header += "#define EMISSION\n";
  if (emission() && shading.plan.emissionTexture) header += "#define EMISSION_TEXTURE\n";
  if (shading.plan.spots) header += "#define SPOT_LIGHTS\n";
  if (shading.plan.falloff) header += "#define FALLOFF_LIGHTS\n";
  if (shading.plan.environment) header += "#define ENVIRONMENT\n";
  if (pass == shading::Pass::ViewDependent && shading.plan.albedo >= 0) header += "#define GGX\n";
  if (maskDepth) header += "#define MASK_DEPTH\n";
  std::string fragment = header + (exact ? kExactFragment : kSliverFragment) + kAttributeHelpers;
  if (pass == shading::Pass::Diffuse) {
    fragment += kDiffuseMain;
  } else {
    fragment += shading::glslLighting() + shading::glslSpecular() + shading::glslEnvironment();
    if (pass == shading::Pass::ViewDependent)
      fragment += kViewDependentMain;
    else if (linear())
      fragment += std::string(shading::glslTextureVector()) + kFinishTexel + kTextureVectorMain;
    else
      fragment += shading::TextureSet::glsl() + kFinishTexel + kTextureDirectMain;
  }
  std::string vertex = header + (exact ? kExactOutputs : kSliverOutputs);
  if (pulled) {
    vertex += "#define NA " + std::to_string(count_) + "\n" +
              PstGeometry::glslPull(GpuVertices::kRecordHead + shading.plan.extraCount,
                                    linear() && !shading.sliceVectors) +
              (exact ? kPulledExactHead : kPulledSliverHead);
    if (linear())
      vertex += exact ? kPulledVectorExactVertex : kPulledVectorSliverVertex;
    else
      vertex += passAttributeGlsl(pass, shading.plan) + (exact ? kPulledExactVertex : kPulledSliverVertex);
  } else
    vertex += exact ? kExactVertex : kSliverVertex;
  program_ = gl::linkProgram(std::string("epi-") + pstModeName(mode) + "-" + shading::passName(pass) +
                                 (pulled ? "-pulled" : ""),
                             {{GL_VERTEX_SHADER, vertex}, {GL_FRAGMENT_SHADER, fragment}});
  vao_ = gl::VertexArray::create();
  if (pass != shading::Pass::Diffuse && shading.scene) shading::setLightUniforms(program_, *shading.scene);
  if (exact && pulled) gl::setUniform(program_, "uEdgeSnap", edgeSnap());
}

bool EpiPass::linear() const {
  return pass_ == shading::Pass::Texture &&
         (shading_.textureMode == TextureMode::Vector || shading_.sliceVectors);
}

bool EpiPass::emission() const {
  return pass_ == shading::Pass::Texture && !maskDepth_ && !shading_.sliceVectors && shading_.plan.emission;
}

bool EpiPass::first() const {
  return maskDepth_ || shading_.sliceVectors || (pass_ == shading::Pass::Diffuse && !shading_.plan.mask);
}

int EpiPass::stride() const {
  return mode_ == PstMode::Exact ? 16 + 8 * chunks() : 8 + 4 * chunks();
}

void EpiPass::gather(const SliceEnd& e, bool front, float* out) const {
  const shading::ShadingPlan& plan = shading_.plan;
  switch (pass_) {
    case shading::Pass::Diffuse: {
      const glm::vec3& c = front ? e.frontOverW : e.backOverW;
      out[0] = c.r, out[1] = c.g, out[2] = c.b;
      return;
    }
    case shading::Pass::Texture:
      std::copy_n(e.extrasOverW.begin() + plan.uv, 2, out);
      return;
    case shading::Pass::ViewDependent:  // one run in the extras (ShadingPlan)
      std::copy_n(e.extrasOverW.begin() + plan.position, count_, out);
      return;
  }
}

float EpiPass::edgeSnap() {
  // Two snapped vertices per edge, each off by up to half a sub-pixel step.
  GLint bits = 4;  // the least GL allows
  gl::GetIntegerv(GL_SUBPIXEL_BITS, &bits);
  return std::ldexp(1.0f, -std::max(bits, 4) + 1);
}

void EpiPass::begin(const glm::vec2& scale, const glm::vec3& eye0, const glm::vec3& eyeStep) const {
  program_.use();
  gl::setUniform(program_, "uScale", scale);
  const GLboolean colour = maskDepth_ ? GL_FALSE : GL_TRUE;
  gl::ColorMask(colour, colour, colour, colour);
  if (first()) {
    gl::Disable(GL_BLEND);
    gl::DepthFunc(GL_GREATER);
    gl::DepthMask(GL_TRUE);
    return;
  }
  gl::DepthFunc(GL_EQUAL);
  gl::DepthMask(GL_FALSE);
  if (pass_ == shading::Pass::Diffuse) {  // after the cut-outs' depth pass: writes the colour
    gl::Disable(GL_BLEND);
    return;
  }
  gl::Enable(GL_BLEND);
  if (pass_ == shading::Pass::Texture) {
    if (emission())
      gl::BlendFuncSeparate(GL_ONE, GL_SRC1_COLOR, GL_ZERO, GL_ONE);  // colour = colour * texel + give-back
    else
      gl::BlendFuncSeparate(GL_DST_COLOR, GL_ZERO, GL_ZERO, GL_ONE);  // colour *= texel
  } else {
    gl::BlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);  // colour += highlight
    gl::setUniform(program_, "uEye0", eye0);
    gl::setUniform(program_, "uEyeStep", eyeStep);
  }
}

void EpiPass::bindVertices(GLuint vertices, GLuint indices) const {
  vao_.vertexBuffer(vertices, GLsizei(stride() * sizeof(float)));
  vao_.elementBuffer(indices);
  for (int offset = 0; offset < stride(); offset += 4)  // every attribute is a vec4
    vao_.attribute(GLuint(offset / 4), 4, GLuint(offset * sizeof(float)));
  vao_.bind();
}

}  // namespace mvr
