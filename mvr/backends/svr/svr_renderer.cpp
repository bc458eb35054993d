// Single viewpoint rendering: the baseline MVR must beat. Lighting runs in
// the vertex shader for every view, as a conventional renderer does.
#include <algorithm>
#include <memory>
#include <vector>

#include "mvr/backends/svr/svr_renderer.h"
#include "mvr/error.h"
#include "mvr/gl/gl_program.h"
#include "mvr/gl/readback_ring.h"
#include "mvr/gl/render_target.h"
#include "mvr/gl/scene_buffers.h"
#include "mvr/image_pool.h"
#include "mvr/views/view_loop.h"
#include "shading/gpu_materials.h"
#include "shading/lighting.h"
#include "shading/shading_plan.h"
#include "shading/view_dependent.h"

namespace mvr {
namespace {


// Vertex stage shared by svr and svr-layered; LAYERED picks the per-view
// matrix from an array by instance.
const char* const kSvrVertex = R"(
#ifdef LAYERED
layout(std430, binding = 0) readonly buffer Views { mat4 uViewProjs[]; };
layout(std430, binding = 2) readonly buffer Eyes { vec4 uEyes[]; };
uniform int uLayerBase;
#ifndef VS_LAYER
flat out int vLayer;
#endif
#else
uniform mat4 uViewProj;
uniform vec3 uEye;
#endif
out vec3 vFront;
out vec3 vBack;
flat out float vCull;
out vec3 vPosition;
out vec3 vNormal;
flat out float vMaterial;
flat out vec3 vEye;
out vec2 vUv;
#ifdef REFLECT
out vec3 vReflect;  // unnormalised, interpolated (Halle eq. 5.2)
#endif
#ifdef GGX
out vec3 vAlbedo;
#endif
void main() {
#ifdef LAYERED
  mat4 viewProj = uViewProjs[uLayerBase + gl_InstanceID];
  vEye = uEyes[uLayerBase + gl_InstanceID].xyz;
#ifdef VS_LAYER
  gl_Layer = gl_InstanceID;
#else
  vLayer = gl_InstanceID;
#endif
#else
  mat4 viewProj = uViewProj;
  vEye = uEye;
#endif
  gl_Position = viewProj * vec4(aPosition, 1.0);
  vFront = surfaceLight(int(aMaterial), aAlbedo, aPosition, aNormal);
  vBack = surfaceLight(int(aMaterial), aAlbedo, aPosition, -aNormal);
  vCull = aCull;
  vPosition = aPosition;
  vNormal = aNormal;
  vMaterial = aMaterial;
  vUv = aUv;
#ifdef REFLECT
  vReflect = reflect(aPosition - vEye, aNormal);
#endif
#ifdef GGX
  vAlbedo = aAlbedo;
#endif
}
)";

// Gouraud diffuse, then, with VIEW_DEPENDENT, the per-pixel highlight for
// this view's eye: the sum the MVR passes accumulate.
const char* const kSvrFragment = R"(
in vec3 vFront;
in vec3 vBack;
flat in float vCull;
in vec3 vPosition;
in vec3 vNormal;
flat in float vMaterial;
flat in vec3 vEye;
in vec2 vUv;
#ifdef REFLECT
in vec3 vReflect;
#endif
#ifdef GGX
in vec3 vAlbedo;
#endif
layout(location = 0) out vec4 oColor;
void main() {
#ifdef TEXTURE
  vec4 texel = surfaceTexel(int(vMaterial), vUv);
#endif
#ifdef EMISSION_TEXTURE
  vec3 glow = surfaceGlow(int(vMaterial), vUv);
#elif defined(EMISSION)
  vec3 glow = materialEmission(int(vMaterial));
#endif
  if (!gl_FrontFacing && vCull > 0.5) discard;
  vec3 c = gl_FrontFacing ? vFront : vBack;
#ifdef TEXTURE
  c *= texel.rgb;
#endif
#ifdef EMISSION
  c += glow;
#endif
#ifdef VIEW_DEPENDENT
  vec3 albedo = vec3(0.0);
#ifdef GGX
  albedo = vAlbedo;
#ifdef TEXTURE
  albedo *= texel.rgb;
#endif
#endif
  vec3 specular, loss;
  viewDependentLight(int(vMaterial), albedo, vPosition, gl_FrontFacing ? vNormal : -vNormal, vEye, specular, loss);
  c += specular;
  c -= loss;
#endif
#ifdef REFLECT
  c += environmentLight(int(vMaterial), vReflect);
#endif
  oColor = vec4(c, 1.0);
}
)";

// Without ARB_shader_viewport_layer_array a geometry shader routes layers.
const char* const kLayerGeometry = R"(
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
flat in int vLayer[];
in vec3 vFront[];
in vec3 vBack[];
flat in float vCull[];
in vec3 vPosition[];
in vec3 vNormal[];
flat in float vMaterial[];
flat in vec3 vEye[];
in vec2 vUv[];
#ifdef REFLECT
in vec3 vReflect[];
out vec3 gReflect;
#endif
#ifdef GGX
in vec3 vAlbedo[];
out vec3 gAlbedo;
#endif
out vec3 gFront;
out vec3 gBack;
flat out float gCull;
out vec3 gPosition;
out vec3 gNormal;
flat out float gMaterial;
flat out vec3 gEye;
out vec2 gUv;
void main() {
  for (int i = 0; i < 3; ++i) {
    gl_Layer = vLayer[0];
    gl_Position = gl_in[i].gl_Position;
    gFront = vFront[i];
    gBack = vBack[i];
    gCull = vCull[i];
    gPosition = vPosition[i];
    gNormal = vNormal[i];
    gMaterial = vMaterial[i];
    gEye = vEye[i];
    gUv = vUv[i];
#ifdef REFLECT
    gReflect = vReflect[i];
#endif
#ifdef GGX
    gAlbedo = vAlbedo[i];
#endif
    EmitVertex();
  }
}
)";

// The plan's passes become defines: one shader computes their sum.
std::string planDefines(const Scene& scene) { return shading::planShading(scene).glslDefines(); }

std::string vertexSource(const Scene& scene, std::initializer_list<std::string_view> defines) {
  std::string header = gl::glslHeader(defines);
  // #extension must precede every declaration.
  for (std::string_view d : defines)
    if (d == "VS_LAYER") header += "#extension GL_ARB_shader_viewport_layer_array : require\n";
  return header + planDefines(scene) + kSceneVertexInputs + shading::glslLighting() + shading::glslMaterials() +
         shading::glslSurfaceLight() + kSvrVertex;
}

// renames: the geometry shader's outputs when it routes layers.
std::string fragmentSource(const Scene& scene, bool renamed) {
  std::string header = gl::glslHeader() + planDefines(scene);
  if (renamed)
    for (const char* name :
         {"Front", "Back", "Cull", "Position", "Normal", "Material", "Eye", "Uv", "Reflect", "Albedo"})
      header += std::string("#define v") + name + " g" + name + "\n";
  return header + shading::glslLighting() + shading::glslSpecular() + shading::TextureSet::glsl() +
         shading::TextureSet::glslSurfaceTexel() + shading::glslEnvironment() + kSvrFragment;
}

class SvrRenderer final : public Renderer {
 public:
  SvrRenderer(const Scene& scene, PixelType type)
      : scene_(scene), type_(type),
        buffers_(scene, shading::vertexAlbedo(scene), shading::vertexCullFlags(scene)),
        program_(gl::linkProgram("svr", {{GL_VERTEX_SHADER, vertexSource(scene, {})},
                                         {GL_FRAGMENT_SHADER, fragmentSource(scene, false)}})),
        materials_(scene, shading::TextureSet::load(scene), shading::EnvironmentSet::load(scene)) {
    shading::setLightUniforms(program_, scene_);
  }
  std::string name() const override { return "svr"; }
  bool sceneMoved() override {  // lit per vertex in the shader: new positions and normals are all
    buffers_.move(scene_);
    return true;
  }
  FrameOrder order() const override { return FrameOrder::View; }

  void render(const ShearingCamera& cam, FrameSink& sink, RenderStats& stats) override {
    RenderTarget target(cam.width(), cam.height(), type_);
    setDepthConvention();
    // The projection flips y (row 0 on top), which turns world-CCW into
    // window-CW: declare CW as front so gl_FrontFacing means camera-facing.
    gl::FrontFace(GL_CW);
    target.bind();
    program_.use();
    materials_.bind();
    buffers_.bind();
    renderEachView(cam, target, sink, stats, [&](int row, int view) {
      ScopedStage s(stats.times, "draw");
      gl::setUniform(program_, "uViewProj", glm::mat4(cam.viewProjection(view, row)));
      gl::setUniform(program_, "uEye", glm::vec3(cam.eye(view, row)));
      target.clear();
      buffers_.draw();
    });
    gl::checkError("svr render");
    stats.counters["draw_calls"] = double(cam.share().rows.size()) * cam.share().views.size();
  }

 private:
  const Scene& scene_;
  PixelType type_;
  SceneBuffers buffers_;
  gl::Program program_;
  shading::GpuMaterials materials_;
};

class LayeredSvrRenderer final : public Renderer {
 public:
  LayeredSvrRenderer(const Scene& scene, PixelType type)
      : scene_(scene), type_(type),
        buffers_(scene, shading::vertexAlbedo(scene), shading::vertexCullFlags(scene)),
        vsLayer_(gl::hasExtension("GL_ARB_shader_viewport_layer_array")),
        materials_(scene, shading::TextureSet::load(scene), shading::EnvironmentSet::load(scene)) {
    if (vsLayer_) {
      program_ = gl::linkProgram(
          "svr-layered", {{GL_VERTEX_SHADER, vertexSource(scene, {"LAYERED", "VS_LAYER"})},
                          {GL_FRAGMENT_SHADER, fragmentSource(scene, false)}});
    } else {
      program_ = gl::linkProgram(
          "svr-layered", {{GL_VERTEX_SHADER, vertexSource(scene, {"LAYERED"})},
                          {GL_GEOMETRY_SHADER, gl::glslHeader() + planDefines(scene) + kLayerGeometry},
                          {GL_FRAGMENT_SHADER, fragmentSource(scene, true)}});
    }
    shading::setLightUniforms(program_, scene_);
  }
  std::string name() const override { return "svr-layered"; }
  bool sceneMoved() override {
    buffers_.move(scene_);
    return true;
  }
  FrameOrder order() const override { return FrameOrder::View; }

  void render(const ShearingCamera& cam, FrameSink& sink, RenderStats& stats) override {
    if (cam.share().rows.size() * cam.share().views.size() == 0) return;
    const int batch = batchSize(cam);
    RenderTarget target(cam.width(), cam.height(), type_, batch);
    std::vector<glm::mat4> matrices;
    std::vector<glm::vec4> eyes;
    std::vector<std::pair<int, int>> frames;  // (row, view) of each layer
    const RenderShare& share = cam.share();
    for (int row = share.rows.begin; row < share.rows.end; ++row)
      for (int view = share.views.begin; view < share.views.end; ++view) {
        matrices.emplace_back(cam.viewProjection(view, row));
        eyes.emplace_back(cam.eye(view, row), 1.0);
        frames.emplace_back(row, view);
      }
    gl::Buffer views = gl::makeBuffer(matrices.data(), matrices.size());
    gl::Buffer eyeBuffer = gl::makeBuffer(eyes.data(), eyes.size());
    views.bindStorage(0);
    eyeBuffer.bindStorage(2);
    materials_.bind();
    setDepthConvention();
    gl::FrontFace(GL_CW);
    target.bind();
    program_.use();
    buffers_.bind();
    const int total = int(matrices.size());
    const size_t layerBytes = size_t(cam.width()) * cam.height() * 4 * Image::channelBytes(type_);
    ReadbackRing ring(size_t(batch) * layerBytes);
    ImagePool pool;
    for (int first = 0; first < total; first += batch) {
      const int count = std::min(batch, total - first);
      {
        ScopedStage s(stats.times, "draw");
        gl::setUniform(program_, "uLayerBase", first);
        target.clear();
        buffers_.draw(count);
      }
      const std::vector<std::shared_ptr<Image>> images = pool.take(count, cam.width(), cam.height(), type_);
      {
        ScopedStage s(stats.times, "readback");
        for (int k = 0; k < count; ++k)
          ring.readLayer(target, k, reinterpret_cast<std::byte*>(images[size_t(k)]->row(0)));
      }
      ring.submit([=, &frames, &sink] {
        for (int k = 0; k < count; ++k) sink.putView(frames[first + k].first, frames[first + k].second, *images[k]);
      });
    }
    ring.drain();
    stats.times.add("gpu_wait", ring.waitSeconds());
    gl::checkError("svr-layered render");
    stats.counters["layers_per_draw"] = batch;
    stats.notes["layer_routing"] = vsLayer_ ? "vertex shader" : "geometry shader";
  }

 private:
  // Bytes of colour and depth per batch of layers; three batches' colour
  // in flight in the readback ring.
  static constexpr size_t kBatchBudget = size_t(64) << 20;

  int batchSize(const ShearingCamera& cam) const {
    GLint maxLayers = 256;
    gl::GetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    const size_t perLayer = size_t(cam.width()) * cam.height() * (4 * Image::channelBytes(type_) + 4);
    const size_t budget = kBatchBudget;
    size_t n = std::max<size_t>(1, budget / perLayer);
    n = std::min({n, size_t(maxLayers), size_t(cam.views()) * cam.rows()});
    return int(n);
  }

  const Scene& scene_;
  PixelType type_;
  SceneBuffers buffers_;
  bool vsLayer_;
  shading::GpuMaterials materials_;
  gl::Program program_;
};

// svr-layered where GL rasterises on the CPU. Layers amortise per-draw and
// per-view overheads a GPU has; llvmpipe has none to amortise, and its
// instanced layered draws cost more per view than single views (143K
// teacup, 64 views: batches of 2 to 64 layers took 1.1x to 2.3x per-view
// svr's time per view). There the strongest conventional renderer is svr,
// and nothing layered is built.
class PerViewLayeredSvrRenderer final : public Renderer {
 public:
  PerViewLayeredSvrRenderer(const Scene& scene, PixelType type) : svr_(scene, type) {}
  std::string name() const override { return "svr-layered"; }
  bool sceneMoved() override { return svr_.sceneMoved(); }
  FrameOrder order() const override { return FrameOrder::View; }
  void render(const ShearingCamera& cam, FrameSink& sink, RenderStats& stats) override {
    svr_.render(cam, sink, stats);
    stats.notes["layer_routing"] = "none: one view per draw (GL renders on the CPU)";
  }

 private:
  SvrRenderer svr_;
};

}  // namespace

std::unique_ptr<Renderer> makeSvrRenderer(const Scene& scene, PixelType type) {
  return std::make_unique<SvrRenderer>(scene, type);
}

std::unique_ptr<Renderer> makeLayeredSvrRenderer(const Scene& scene, PixelType type, bool forceLayers) {
  if (gl::rendersOnCpu() && !forceLayers) return std::make_unique<PerViewLayeredSvrRenderer>(scene, type);
  return std::make_unique<LayeredSvrRenderer>(scene, type);
}

}  // namespace mvr
