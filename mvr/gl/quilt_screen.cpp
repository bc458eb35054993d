#include "mvr/gl/quilt_screen.h"

#include <cstring>
#include <vector>

#include "mvr/error.h"
#include "mvr/gl/gl_program.h"

namespace mvr {

namespace {

// The quilt over the whole screen, linearly filtered (row 0 of the
// texture is the quilt's top row, as uploaded).
const char* const kScaled = R"(
layout(binding = 0) uniform sampler2D quilt;
uniform vec2 screenSize;
layout(location = 0) out vec4 color;
void main() {
  vec2 uv = vec2(gl_FragCoord.x, screenSize.y - gl_FragCoord.y) / screenSize;
  color = vec4(texture(quilt, uv).rgb, 1.0);
}
)";

}  // namespace

QuiltScreen::QuiltScreen(int width, int height, int quiltWidth, int quiltHeight, std::optional<LenticularMap> panel,
                         bool offscreen)
    : width_(width), height_(height), quiltWidth_(quiltWidth), quiltHeight_(quiltHeight), quilt_(GL_TEXTURE_2D),
      vao_(gl::VertexArray::create()) {
  gl::TextureStorage2D(quilt_.id(), 1, GL_RGBA8, quiltWidth, quiltHeight);
  gl::TextureParameteri(quilt_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl::TextureParameteri(quilt_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  if (panel) {
    if (panel->screenW != width || panel->screenH != height) fail("live", "the screen is not the panel's size");
    panel_ = std::make_unique<LenticularPass>(*panel);
  } else {
    scaled_ = gl::linkProgram("quilt screen", {{GL_VERTEX_SHADER, gl::glslHeader() + gl::kFullScreenTriangleVertex},
                                               {GL_FRAGMENT_SHADER, gl::glslHeader() + kScaled}});
    gl::setUniform(scaled_, "screenSize", glm::vec2(float(width), float(height)));
  }
  if (offscreen) {
    target_ = gl::Texture(GL_TEXTURE_2D);
    gl::TextureStorage2D(target_.id(), 1, GL_RGBA8, width, height);
    fbo_ = gl::Framebuffer::create();
    gl::NamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, target_.id(), 0);
  }
}

void QuiltScreen::upload(const Image& quilt) {
  if (quilt.width != quiltWidth_ || quilt.height != quiltHeight_ || !isByteType(quilt.type))
    fail("live", "a quilt of another size or type");
  gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl::TextureSubImage2D(quilt_.id(), 0, 0, 0, quiltWidth_, quiltHeight_, GL_RGBA, GL_UNSIGNED_BYTE, quilt.bytes.data());
}

void QuiltScreen::draw() const {
  gl::BindFramebuffer(GL_FRAMEBUFFER, fbo_ ? fbo_.id() : 0);
  if (panel_) {
    panel_->draw(quilt_.id());
    return;
  }
  gl::Viewport(0, 0, width_, height_);
  gl::Disable(GL_DEPTH_TEST);
  gl::Disable(GL_BLEND);
  gl::Disable(GL_FRAMEBUFFER_SRGB);  // the quilt holds display values already
  gl::UseProgram(scaled_.id());
  gl::BindTextureUnit(0, quilt_.id());
  gl::BindVertexArray(vao_.id());
  gl::DrawArrays(GL_TRIANGLES, 0, 3);
}

void QuiltScreen::finish() const { gl::Finish(); }

Image QuiltScreen::read() const {
  Image out(width_, height_, PixelType::Srgb8);
  std::vector<uint8_t> raw(out.bytes.size());
  gl::BindFramebuffer(GL_READ_FRAMEBUFFER, fbo_ ? fbo_.id() : 0);
  gl::PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl::ReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, raw.data());
  for (int y = 0; y < height_; ++y)  // GL's rows run up
    std::memcpy(out.row(y), raw.data() + size_t(height_ - 1 - y) * out.rowBytes(), out.rowBytes());
  return out;
}

}  // namespace mvr
