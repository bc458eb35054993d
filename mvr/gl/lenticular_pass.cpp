#include "mvr/gl/lenticular_pass.h"

#include <iterator>

#include "mvr/error.h"
#include "mvr/gl/gl_program.h"
#include "mvr/gl/render_target.h"

namespace mvr {

namespace {

const char* const kMain = R"(
uniform int screenH;
layout(location = 0) out vec4 color;
void main() {
  ivec2 pixel = ivec2(int(gl_FragCoord.x), screenH - 1 - int(gl_FragCoord.y));
  color = vec4(lenticular(pixel), 1.0);
}
)";

}  // namespace

LenticularPass::LenticularPass(const LenticularMap& map, ViewLayout layout)
    : map_(map), layout_(layout), vao_(gl::VertexArray::create()) {
  program_ = gl::linkProgram("lenticular", {{GL_VERTEX_SHADER, gl::glslHeader() + gl::kFullScreenTriangleVertex},
                                            {GL_FRAGMENT_SHADER, gl::glslHeader() + lenticularGlsl(layout) + kMain}});
  const LenticularMap& m = map_;
  for (const auto& [name, v] : {std::pair{"invW", m.invW}, {"invH", m.invH}, {"subp", m.subp}, {"tilt", m.tilt},
                                {"pitch", m.pitch}, {"center", m.center}})
    gl::setUniform(program_, name, v);
  for (const auto& [name, v] : {std::pair{"views", m.views}, {"columns", m.columns}, {"tileW", m.tileW},
                                {"tileH", m.tileH}, {"quiltHeight", m.quiltHeight}, {"ri", m.ri}, {"bi", m.bi},
                                {"invView", int(m.invView)}, {"flipX", int(m.flipX)}, {"flipY", int(m.flipY)},
                                {"screenH", m.screenH}, {"quilt", 0}})
    gl::setUniform(program_, name, v);
}

void LenticularPass::draw(GLuint quiltTexture) const {
  gl::Viewport(0, 0, map_.screenW, map_.screenH);
  gl::Disable(GL_DEPTH_TEST);
  gl::Disable(GL_BLEND);
  gl::Disable(GL_FRAMEBUFFER_SRGB);  // the quilt holds display values already
  gl::UseProgram(program_.id());
  gl::BindTextureUnit(0, quiltTexture);
  gl::BindVertexArray(vao_.id());
  gl::DrawArrays(GL_TRIANGLES, 0, 3);
}

namespace {

// The GL state the pass changes, put back when it is done: a renderer
// drawing next in the same context (a sequence's next frame) finds its own.
class SavedState {
 public:
  SavedState() {
    gl::GetIntegerv(GL_VIEWPORT, viewport_);
    gl::GetIntegerv(GL_CURRENT_PROGRAM, &program_);
    gl::GetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao_);
    gl::GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_);
    gl::GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_);
    for (size_t i = 0; i < std::size(kCaps); ++i) enabled_[i] = gl::IsEnabled(kCaps[i]);
  }
  ~SavedState() {
    gl::Viewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
    gl::UseProgram(GLuint(program_));
    gl::BindVertexArray(GLuint(vao_));
    gl::BindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw_));
    gl::BindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read_));
    for (size_t i = 0; i < std::size(kCaps); ++i) {
      if (enabled_[i])
        gl::Enable(kCaps[i]);
      else
        gl::Disable(kCaps[i]);
    }
  }

 private:
  static constexpr GLenum kCaps[] = {GL_DEPTH_TEST, GL_BLEND, GL_FRAMEBUFFER_SRGB};
  GLint viewport_[4] = {}, program_ = 0, vao_ = 0, draw_ = 0, read_ = 0;
  bool enabled_[std::size(kCaps)] = {};
};

}  // namespace

namespace {

gl::Texture uploadViews(const Image& views, ViewLayout layout, int layers) {
  gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (layout == ViewLayout::Quilt) {
    gl::Texture t(GL_TEXTURE_2D);
    gl::TextureStorage2D(t.id(), 1, GL_RGBA8, views.width, views.height);
    gl::TextureSubImage2D(t.id(), 0, 0, 0, views.width, views.height, GL_RGBA, GL_UNSIGNED_BYTE, views.bytes.data());
    return t;
  }
  gl::Texture t(GL_TEXTURE_2D_ARRAY);
  const int rows = views.height / layers;
  gl::TextureStorage3D(t.id(), 1, GL_RGBA8, views.width, rows, layers);
  gl::TextureSubImage3D(t.id(), 0, 0, 0, 0, views.width, rows, layers, GL_RGBA, GL_UNSIGNED_BYTE, views.bytes.data());
  return t;
}

}  // namespace

Image LenticularPass::render(const Image& views) const {
  const bool layered = layout_ != ViewLayout::Quilt;
  if (!isByteType(views.type) || (layered ? views.width != map_.tileW || views.height != map_.tileH * map_.views
                                          : views.height != map_.quiltHeight))
    fail("quilt", "does not match the mapping's layout");
  const SavedState saved;
  gl::Texture source = uploadViews(views, layout_, layout_ == ViewLayout::EpiVolume ? map_.tileH : map_.views);
  gl::Texture target(GL_TEXTURE_2D);
  gl::TextureStorage2D(target.id(), 1, GL_RGBA8, map_.screenW, map_.screenH);
  gl::Framebuffer fbo = gl::Framebuffer::create();
  gl::NamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, target.id(), 0);
  gl::BindFramebuffer(GL_FRAMEBUFFER, fbo.id());
  draw(source.id());
  Image out = readFramebuffer(fbo.id(), map_.screenW, map_.screenH);
  out.type = views.type;
  return out;
}

}  // namespace mvr
