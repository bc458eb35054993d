#include "mvr/views/deferred_pipeline.h"

#include <utility>

#include "mvr/error.h"
#include "shading/lighting.h"
#include "shading/view_dependent.h"

namespace mvr {
namespace {

const char* const kGeometryVertex = R"(
uniform mat4 uViewProj;
out vec3 vNormal;
out vec3 vAlbedo;
flat out float vCull;
flat out float vMaterial;
out vec2 vUv;
void main() {
  gl_Position = uViewProj * vec4(aPosition, 1.0);
  vNormal = aNormal;
  vAlbedo = aAlbedo;
  vCull = aCull;
  vMaterial = aMaterial;
  vUv = aUv;
}
)";

// Coverage as the geometry pass decides it, nothing written but depth.
const char* const kDepthFragment = R"(
flat in float vCull;
void main() {
  if (!gl_FrontFacing && vCull > 0.5) discard;
}
)";

// Depth peeling with de Quilletes' extended offset d s / (E - s): a
// surface closer behind the last layer than that never moves a pixel away
// from it anywhere on a track of width E, so it is not a new layer. One
// function for the peeling pass and the fragment lists' resolve, so that
// both round alike; it defines PEEL for the shader that follows.
const char* const kPeelTest = R"(
#define PEEL
layout(binding = 6) uniform sampler2D uPreviousDepth;
uniform vec4 uPeel;  // near, far, pixel footprint per unit distance, track width E
float distanceOf(float depth) { return uPeel.x * uPeel.y / (depth * (uPeel.y - uPeel.x) + uPeel.x); }
// Whether a fragment at window depth `depth` lies in the layer behind the
// one whose depth here is `previous` (0: nothing in front, nothing behind).
bool behindLayer(float previous, float depth) {
  if (previous == 0.0) return false;
  float d = distanceOf(previous), s = uPeel.z * d;
  return !(uPeel.w <= s || distanceOf(depth) <= d + d * s / (uPeel.w - s));
}
)";

const char* const kGeometryFragment = R"(
in vec3 vNormal;
in vec3 vAlbedo;
flat in float vCull;
flat in float vMaterial;
in vec2 vUv;
#ifndef COLLECT
layout(location = 0) out vec4 oAlbedo;  // a = 1 marks covered pixels
layout(location = 1) out vec4 oNormal;  // w: material index
#ifdef EMISSION_TEXTURE
layout(location = 2) out vec4 oGlow;
#endif
#endif
void main() {
#ifdef TEXTURE
  vec4 texel = surfaceTexel(int(vMaterial), vUv);
#endif
#if defined(EMISSION_TEXTURE) && !defined(COLLECT)
  oGlow = vec4(surfaceGlow(int(vMaterial), vUv), 1.0);
#endif
  if (!gl_FrontFacing && vCull > 0.5) discard;
#ifdef PEEL
  if (!behindLayer(texelFetch(uPreviousDepth, ivec2(gl_FragCoord.xy), 0).r, gl_FragCoord.z)) discard;
#endif
  vec3 albedo = vAlbedo;
#ifdef TEXTURE
  albedo *= texel.rgb;
#endif
  vec4 normal = vec4(gl_FrontFacing ? vNormal : -vNormal, vMaterial);
#ifdef COLLECT
  append(albedo, normal);
#else
  oAlbedo = vec4(albedo, 1.0);
  oNormal = normal;
#endif
}
)";

// The layer a peeling geometry pass keeps (previous: the layer in front's
// G-buffer; none: the nearest), taken from the fragment lists of one
// collecting pass: the fragments the peel keeps, met as its depth test
// would meet them.
const char* const kResolveFragment = R"(
layout(location = 0) out vec4 oAlbedo;
layout(location = 1) out vec4 oNormal;
void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  ListHead head = listHead(px);
#ifdef PEEL
  float previous = texelFetch(uPreviousDepth, px, 0).r;
#endif
  // Counted, not walked to kListEnd, and nothing discarded before the
  // loop: llvmpipe ran the lanes it had masked off on to its loop limit.
  uint best = kListEnd, bestPrimitive = 0u, i = head.first;
  float bestDepth = 0.0;  // the cleared depth buffer's
  for (uint n = 0u; n < head.count; ++n, i = uListLink[i].y) {
    float depth = uListSurface[i].w;
#ifdef PEEL
    if (!behindLayer(previous, depth)) continue;
#endif
    // GL_GREATER, primitives met in order: the nearest wins, and of equals
    // the first drawn.
    uint primitive = uListLink[i].x;
    if (depth > bestDepth || (depth == bestDepth && best != kListEnd && primitive < bestPrimitive)) {
      best = i;
      bestDepth = depth;
      bestPrimitive = primitive;
    }
  }
  if (best == kListEnd) discard;
  oAlbedo = vec4(uListSurface[best].rgb, 1.0);
  oNormal = uListNormal[best];
  gl_FragDepth = bestDepth;
}
)";

const char* const kLightingFragment = R"(
layout(binding = 0) uniform sampler2D uAlbedo;
layout(binding = 1) uniform sampler2D uNormal;
layout(binding = 2) uniform sampler2D uDepth;
#ifdef EMISSION_TEXTURE
layout(binding = 3) uniform sampler2D uGlow;
#endif
uniform mat4 uInverseViewProj;
uniform vec2 uSize;
uniform vec3 uEye;
layout(location = 0) out vec4 oColor;
void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 albedo = texelFetch(uAlbedo, px, 0);
  if (albedo.a == 0.0) discard;
  float depth = texelFetch(uDepth, px, 0).r;  // zero-to-one clip depth
  vec4 ndc = vec4(gl_FragCoord.xy / uSize * 2.0 - 1.0, depth, 1.0);
  vec4 world = uInverseViewProj * ndc;
  vec4 normal = texelFetch(uNormal, px, 0);
  vec3 n = normalize(normal.xyz), p = world.xyz / world.w;
  vec3 c = surfaceLight(int(normal.w + 0.5), albedo.rgb, p, n);
#ifdef EMISSION_TEXTURE
  c += texelFetch(uGlow, px, 0).rgb;
#elif defined(EMISSION)
  c += materialEmission(int(normal.w + 0.5));
#endif
#if defined(VIEW_DEPENDENT) && !defined(SEPARATE_HIGHLIGHTS)
  vec3 specular, loss;
  viewDependentLight(int(normal.w + 0.5), albedo.rgb, p, n, uEye, specular, loss);
  c += specular;
  c -= loss;
#elif defined(GGX)
  c -= diffuseFresnelLoss(int(normal.w + 0.5), albedo.rgb, p, n, uEye);
#endif
#ifdef REFLECT
  // Per pixel from the G-buffer's normal, unlike the interpolated
  // per-vertex reflection vectors of svr and mvr (Halle eq. 5.2).
  c += environmentLight(int(normal.w + 0.5), reflect(p - uEye, n));
#endif
  oColor = vec4(c, 1.0);
}
)";

}  // namespace

GBuffer::GBuffer(int w, int h, bool exactAlbedo, bool glow)
    : width_(w), height_(h), albedo_(GL_TEXTURE_2D), normal_(GL_TEXTURE_2D), depth_(GL_TEXTURE_2D),
      glow_(glow ? gl::Texture(GL_TEXTURE_2D) : gl::Texture()), fbo_(gl::Framebuffer::create()) {
  albedo_.storage2D(exactAlbedo ? GL_RGBA32F : GL_RGBA8, w, h);
  normal_.storage2D(GL_RGBA16F, w, h);
  depth_.storage2D(GL_DEPTH_COMPONENT32F, w, h);
  fbo_.attach(GL_COLOR_ATTACHMENT0, albedo_.id(), 0);
  fbo_.attach(GL_COLOR_ATTACHMENT1, normal_.id(), 0);
  fbo_.attach(GL_DEPTH_ATTACHMENT, depth_.id(), 0);
  if (glow) {
    // Emission is in [0, 1] (Material), but float keeps the sum exact.
    glow_.storage2D(GL_RGBA16F, w, h);
    fbo_.attach(GL_COLOR_ATTACHMENT2, glow_.id(), 0);
    fbo_.drawBuffers({GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2});
  } else {
    fbo_.drawBuffers({GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1});
  }
  if (!fbo_.complete())
    fail("GL", "G-buffer is incomplete");
}

GBuffer GBuffer::depthOnly(int width, int height) { return GBuffer(width, height, DepthOnly{}); }

GBuffer::GBuffer(int w, int h, DepthOnly)
    : width_(w), height_(h), depth_(GL_TEXTURE_2D), fbo_(gl::Framebuffer::create()), colour_(false) {
  depth_.storage2D(GL_DEPTH_COMPONENT32F, w, h);
  fbo_.attach(GL_DEPTH_ATTACHMENT, depth_.id(), 0);
  fbo_.drawBuffers({GL_NONE});
  if (!fbo_.complete())
    fail("GL", "depth-only G-buffer is incomplete");
}

void GBuffer::bindForWriting() const {
  fbo_.bind();
  gl::Viewport(0, 0, width_, height_);
  const float zero[4] = {0, 0, 0, 0};
  if (colour_) {
    gl::ClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 0, zero);
    gl::ClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 1, zero);
    if (glow_.id()) gl::ClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 2, zero);
  }
  gl::ClearNamedFramebufferfi(fbo_.id(), GL_DEPTH_STENCIL, 0, 0.0f, 0);
}

DeferredPipeline::DeferredPipeline(const Scene& scene, bool separateHighlights)
    : buffers_(scene, shading::vertexAlbedo(scene), shading::vertexCullFlags(scene)),
      plan_(shading::planShading(scene)),
      geometry_(geometryProgram("deferred-geometry", "")),
      lighting_(gl::linkProgram(
          "deferred-lighting",
          {{GL_VERTEX_SHADER, gl::glslHeader() + gl::kFullScreenTriangleVertex},
           {GL_FRAGMENT_SHADER, header() + (separateHighlights ? "#define SEPARATE_HIGHLIGHTS\n" : "") +
                                    shading::glslLighting() + shading::glslSpecular() +
                                    shading::glslSurfaceLight() + shading::glslEnvironment() +
                                    kLightingFragment}})),
      emptyVao_(gl::VertexArray::create()),
      materials_(scene, shading::TextureSet::load(scene), shading::EnvironmentSet::load(scene)),
      exactAlbedo_(scene.exactColors) {
  shading::setLightUniforms(lighting_, scene);
}

void DeferredPipeline::begin(int width, int height, IndexRange rows) {
  rows_ = rows.end < 0 ? IndexRange{0, height} : rows;
  width_ = width, height_ = height;
  setDepthConvention();
  gl::FrontFace(GL_CW);
  gl::setUniform(lighting_, "uSize", glm::vec2(width, height));
  materials_.bind();
}

template <class Draw>
void DeferredPipeline::inRows(Draw&& draw) {
  gl::Enable(GL_SCISSOR_TEST);
  gl::Scissor(0, rows_.begin, width_, rows_.size());
  if (condition_) gl::BeginConditionalRender(condition_, GL_QUERY_WAIT);
  draw();
  if (condition_) gl::EndConditionalRender();
  gl::Disable(GL_SCISSOR_TEST);
}

void DeferredPipeline::geometry(const glm::dmat4& viewProj, const GBuffer& gbuffer,
                                const GBuffer* previous, const glm::vec4& peel) {
  gbuffer.bindForWriting();
  gl::Enable(GL_DEPTH_TEST);
  const gl::Program* program = &geometry_;
  if (previous) {
    if (!peeling_.id()) peeling_ = geometryProgram("deferred-geometry-peel", kPeelTest);
    program = &peeling_;
    gl::bindTexture(6, previous->depthTexture());
    gl::setUniform(peeling_, "uPeel", peel);
  }
  program->use();
  gl::setUniform(*program, "uViewProj", glm::mat4(viewProj));
  buffers_.bind();
  inRows([&] { buffers_.draw(); });
}

bool DeferredPipeline::collect(const glm::dmat4& viewProj) {
  if (plan_.emissionTexture) return false;
  if (!collect_.id())
    collect_ = geometryProgram("deferred-geometry-collect", std::string("#define COLLECT\n") + FragmentLists::glsl());
  for (;;) {
    lists_.beginCollect(width_, height_);
    gl::Disable(GL_DEPTH_TEST);  // every fragment, not the nearest
    collect_.use();
    gl::setUniform(collect_, "uViewProj", glm::mat4(viewProj));
    buffers_.bind();
    const GLuint condition = std::exchange(condition_, 0);
    inRows([&] { buffers_.draw(); });
    condition_ = condition;
    switch (lists_.check()) {
      case FragmentLists::Fit::Fits: return true;
      case FragmentLists::Fit::TooLarge: return false;
      case FragmentLists::Fit::Grown: break;  // drawn again with room
    }
  }
}

void DeferredPipeline::resolve(const GBuffer& gbuffer, const GBuffer* previous, const glm::vec4& peel) {
  gl::Program& program = previous ? resolvePeel_ : resolve_;
  if (!program.id())
    program = gl::linkProgram(
        previous ? "deferred-resolve-peel" : "deferred-resolve",
        {{GL_VERTEX_SHADER, gl::glslHeader() + gl::kFullScreenTriangleVertex},
         {GL_FRAGMENT_SHADER, gl::glslHeader() + (previous ? kPeelTest : "") + FragmentLists::glsl() +
                                  kResolveFragment}});
  gbuffer.bindForWriting();
  gl::Enable(GL_DEPTH_TEST);
  gl::DepthFunc(GL_ALWAYS);  // the shader picks the fragment the depth test would
  program.use();
  if (previous) {
    gl::bindTexture(6, previous->depthTexture());
    gl::setUniform(program, "uPeel", peel);
  }
  lists_.bindForReading();
  emptyVao_.bind();
  inRows([] { gl::DrawArrays(GL_TRIANGLES, 0, 3); });
  gl::DepthFunc(GL_GREATER);
}

void DeferredPipeline::depth(const glm::dmat4& viewProj, const GBuffer& target,
                             const std::vector<uint32_t>* triangles) {
  if (!depth_.id())
    depth_ = gl::linkProgram("deferred-depth", {{GL_VERTEX_SHADER, gl::glslHeader() + kSceneVertexInputs + kGeometryVertex},
                                                {GL_FRAGMENT_SHADER, gl::glslHeader() + kDepthFragment}});
  target.bindForWriting();
  gl::Enable(GL_DEPTH_TEST);
  depth_.use();
  gl::setUniform(depth_, "uViewProj", glm::mat4(viewProj));
  buffers_.bind();
  if (!triangles) return inRows([&] { buffers_.draw(); });
  const gl::Buffer subset = gl::makeBuffer(triangles->data(), triangles->size());
  inRows([&] { buffers_.draw(subset, GLsizei(triangles->size())); });
}

void DeferredPipeline::lighting(const glm::dmat4& viewProj, const glm::dvec3& eye,
                                const GBuffer& gbuffer, const RenderTarget& target) {
  target.bind();
  target.clear();
  gl::Disable(GL_DEPTH_TEST);
  lighting_.use();
  gl::setUniform(lighting_, "uInverseViewProj", glm::mat4(glm::inverse(viewProj)));
  gl::setUniform(lighting_, "uEye", glm::vec3(eye));
  gbuffer.bindForReading();
  emptyVao_.bind();
  inRows([] { gl::DrawArrays(GL_TRIANGLES, 0, 3); });
}

std::string DeferredPipeline::header() const { return gl::glslHeader() + plan_.glslDefines(); }

gl::Program DeferredPipeline::geometryProgram(const char* name, const std::string& prelude) const {
  return gl::linkProgram(name, {{GL_VERTEX_SHADER, gl::glslHeader() + kSceneVertexInputs + kGeometryVertex},
                                {GL_FRAGMENT_SHADER, header() + prelude + shading::glslLighting() +
                                                         shading::glslSpecular() + shading::TextureSet::glsl() +
                                                         shading::TextureSet::glslSurfaceTexel() + kGeometryFragment}});
}

}  // namespace mvr
