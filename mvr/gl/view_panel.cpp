#include "mvr/gl/view_panel.h"

#include "mvr/gl/gl_program.h"
#include "mvr/gl/render_target.h"

namespace mvr::gl {

namespace {

// Top: the view, 1:1. Below: the EPI (views down), scaled to the panel.
const char* const kPanelFragment = R"(
layout(binding = 0) uniform sampler2D uView;
layout(binding = 1) uniform sampler2D uEpi;
uniform ivec2 uViewSize;
uniform int uEpiRows;    // EPI texture height: the view count
uniform int uPanelRows;  // window rows given to the EPI
uniform int uWindowRows;
uniform ivec2 uMarker;   // x: view row in the EPI, y: scanline; -1: none
layout(location = 0) out vec4 oColor;
// Over black, opaque: what a display shows, and screenshots without holes.
vec4 opaque(vec4 c) { return vec4(c.rgb * c.a, 1.0); }
void main() {
  int x = int(gl_FragCoord.x);
  int fromTop = uWindowRows - 1 - int(gl_FragCoord.y);
  if (fromTop < uViewSize.y) {
    oColor = opaque(texelFetch(uView, ivec2(x, fromTop), 0));
    if (fromTop == uMarker.y) oColor = mix(oColor, vec4(1, 1, 0, 1), 0.5);
  } else {
    int e = fromTop - uViewSize.y;
    int src = min(uEpiRows - 1, e * uEpiRows / uPanelRows);
    oColor = opaque(texelFetch(uEpi, ivec2(x, src), 0));
    if (src == uMarker.x) oColor = mix(oColor, vec4(1, 1, 0, 1), 0.5);
  }
}
)";

}  // namespace

ViewPanel::ViewPanel(int width, int height, int views, int panelRows)
    : width_(width), height_(height), views_(views), panelRows_(panelRows), view_(GL_TEXTURE_2D),
      epi_(GL_TEXTURE_2D), vao_(VertexArray::create()) {
  program_ = linkProgram("viewer", {{GL_VERTEX_SHADER, glslHeader() + kFullScreenTriangleVertex},
                                    {GL_FRAGMENT_SHADER, glslHeader() + kPanelFragment}});
  TextureStorage2D(view_.id(), 1, GL_RGBA8, width, height);
  TextureStorage2D(epi_.id(), 1, GL_RGBA8, width, views);
}

void ViewPanel::upload(const Image& view, const Image& epi) {
  PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  TextureSubImage2D(view_.id(), 0, 0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, view.bytes.data());
  TextureSubImage2D(epi_.id(), 0, 0, 0, width_, views_, GL_RGBA, GL_UNSIGNED_BYTE, epi.bytes.data());
}

void ViewPanel::draw(glm::ivec2 marker) {
  BindFramebuffer(GL_FRAMEBUFFER, 0);
  Viewport(0, 0, width_, windowRows());
  Disable(GL_DEPTH_TEST);
  Disable(GL_FRAMEBUFFER_SRGB);  // the textures hold display values already
  UseProgram(program_.id());
  setUniform(program_, "uEpiRows", views_);
  setUniform(program_, "uPanelRows", panelRows_);
  setUniform(program_, "uWindowRows", windowRows());
  ProgramUniform2i(program_.id(), GetUniformLocation(program_.id(), "uViewSize"), width_, height_);
  ProgramUniform2i(program_.id(), GetUniformLocation(program_.id(), "uMarker"), marker.x, marker.y);
  BindTextureUnit(0, view_.id());
  BindTextureUnit(1, epi_.id());
  BindVertexArray(vao_.id());
  DrawArrays(GL_TRIANGLES, 0, 3);
  Finish();
}

Image ViewPanel::read() const { return readFramebuffer(0, width_, windowRows()); }

}  // namespace mvr::gl
