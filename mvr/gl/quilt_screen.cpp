#include "mvr/gl/quilt_screen.h"

#include "mvr/error.h"
#include "mvr/gl/gl_program.h"
#include "mvr/gl/render_target.h"

namespace mvr {

namespace {

// The quilt over the whole screen, linearly filtered (row 0 of the
// texture is the quilt's top row, as uploaded); from an EPI volume or a
// view array, the quilt's texel nearest to each screen pixel.
const char* const kScaled = R"(
#if defined(EPI_VOLUME) || defined(VIEW_ARRAY)
layout(binding = 0) uniform sampler2DArray quilt;
#else
layout(binding = 0) uniform sampler2D quilt;
#endif
uniform vec2 screenSize;
uniform ivec4 grid;  // columns, tile rows, tile width, tile height
uniform int views;
layout(location = 0) out vec4 color;
void main() {
  vec2 uv = vec2(gl_FragCoord.x, screenSize.y - gl_FragCoord.y) / screenSize;
#if defined(EPI_VOLUME) || defined(VIEW_ARRAY)
  ivec2 q = ivec2(uv * vec2(grid.xy * grid.zw));  // the quilt's pixel, y down
  ivec2 tile = q / grid.zw, in_tile = q % grid.zw;
  int view = (grid.y - 1 - tile.y) * grid.x + tile.x;
#ifdef EPI_VOLUME
  ivec3 at = ivec3(in_tile.x, view, in_tile.y);
#else
  ivec3 at = ivec3(in_tile, view);
#endif
  color = view < views ? vec4(texelFetch(quilt, at, 0).rgb, 1.0) : vec4(0, 0, 0, 1);
#else
  color = vec4(texture(quilt, uv).rgb, 1.0);
#endif
}
)";

}  // namespace

QuiltScreen::QuiltScreen(int width, int height, const QuiltGrid& grid, ViewLayout layout,
                         std::optional<LenticularMap> panel, bool offscreen)
    : width_(width), height_(height), grid_(grid), layout_(layout),
      uploadWidth_(layout == ViewLayout::Quilt ? grid.columns * grid.tileWidth : grid.tileWidth),
      uploadHeight_(layout == ViewLayout::Quilt ? grid.rows * grid.tileHeight : grid.tileHeight * grid.views),
      quilt_(layout == ViewLayout::Quilt ? GL_TEXTURE_2D : GL_TEXTURE_2D_ARRAY), vao_(gl::VertexArray::create()) {
  const glm::ivec3 box = layerBox();
  if (layout == ViewLayout::Quilt)
    gl::TextureStorage2D(quilt_.id(), 1, GL_RGBA8, uploadWidth_, uploadHeight_);
  else
    gl::TextureStorage3D(quilt_.id(), 1, GL_RGBA8, box.x, box.y, box.z);
  gl::TextureParameteri(quilt_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl::TextureParameteri(quilt_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  if (panel) {
    if (panel->screenW != width || panel->screenH != height) fail("live", "the screen is not the panel's size");
    panel_ = std::make_unique<LenticularPass>(*panel, layout);
  } else {
    const std::string defines =
        gl::glslHeader(layout == ViewLayout::EpiVolume   ? std::initializer_list<std::string_view>{"EPI_VOLUME"}
                       : layout == ViewLayout::ViewArray ? std::initializer_list<std::string_view>{"VIEW_ARRAY"}
                                                         : std::initializer_list<std::string_view>{});
    scaled_ = gl::linkProgram("quilt screen", {{GL_VERTEX_SHADER, gl::glslHeader() + gl::kFullScreenTriangleVertex},
                                               {GL_FRAGMENT_SHADER, defines + kScaled}});
    gl::setUniform(scaled_, "screenSize", glm::vec2(float(width), float(height)));
    gl::setUniform(scaled_, "views", grid.views);
    gl::ProgramUniform4i(scaled_.id(), scaled_.location("grid"), grid.columns, grid.rows, grid.tileWidth,
                         grid.tileHeight);
  }
  if (offscreen) {
    target_ = gl::Texture(GL_TEXTURE_2D);
    gl::TextureStorage2D(target_.id(), 1, GL_RGBA8, width, height);
    fbo_ = gl::Framebuffer::create();
    gl::NamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, target_.id(), 0);
  }
}

void QuiltScreen::upload(const Image& views) {
  if (views.width != uploadWidth_ || views.height != uploadHeight_ || !isByteType(views.type))
    fail("live", "views of another size or type");
  gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (layout_ == ViewLayout::Quilt)
    gl::TextureSubImage2D(quilt_.id(), 0, 0, 0, uploadWidth_, uploadHeight_, GL_RGBA, GL_UNSIGNED_BYTE,
                          views.bytes.data());
  else
    gl::TextureSubImage3D(quilt_.id(), 0, 0, 0, 0, layerBox().x, layerBox().y, layerBox().z, GL_RGBA,
                          GL_UNSIGNED_BYTE, views.bytes.data());
}

glm::ivec3 QuiltScreen::layerBox() const {
  return layout_ == ViewLayout::EpiVolume ? glm::ivec3(grid_.tileWidth, grid_.views, grid_.tileHeight)
                                          : glm::ivec3(grid_.tileWidth, grid_.tileHeight, grid_.views);
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

Image QuiltScreen::read() const { return readFramebuffer(fbo_ ? fbo_.id() : 0, width_, height_); }

}  // namespace mvr
