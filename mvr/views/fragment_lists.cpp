#include "mvr/views/fragment_lists.h"

#include <algorithm>

#include "mvr/error.h"

namespace mvr {
namespace {

// The header holds the count (which goes on past the capacity, so that
// check() learns how much room the pass needed), the capacity and the
// row length of the heads.
const char* const kLists = R"(
layout(std430, binding = 2) buffer ListHeader { uint uListCount; uint uListCapacity; int uListWidth; };
struct ListHead { uint first, count; };  // the last fragment appended, and how many
layout(std430, binding = 3) buffer ListHeads { ListHead uListHeads[]; };
layout(std430, binding = 4) buffer ListSurface { vec4 uListSurface[]; };  // albedo, window depth
layout(std430, binding = 5) buffer ListNormal { vec4 uListNormal[]; };    // normal of the side seen, material
layout(std430, binding = 6) buffer ListLink { uvec2 uListLink[]; };       // primitive, next fragment
const uint kListEnd = 0xffffffffu;
ListHead listHead(ivec2 px) { return uListHeads[px.y * uListWidth + px.x]; }
#ifdef COLLECT
void append(vec3 albedo, vec4 normal) {
  uint i = atomicAdd(uListCount, 1u);
  if (i >= uListCapacity) return;
  ivec2 px = ivec2(gl_FragCoord.xy);
  uListSurface[i] = vec4(albedo, gl_FragCoord.z);
  uListNormal[i] = normal;
  uint at = uint(px.y * uListWidth + px.x);
  uListLink[i] = uvec2(uint(gl_PrimitiveID), atomicExchange(uListHeads[at].first, i));
  atomicAdd(uListHeads[at].count, 1u);
}
#endif
)";

size_t gMaxBytes = FragmentLists::kMaxBytes;

struct Header {
  uint32_t count, capacity;
  int32_t width;
};

}  // namespace

const char* FragmentLists::glsl() { return kLists; }

void FragmentLists::setMaxBytes(size_t bytes) { gMaxBytes = bytes; }

void FragmentLists::allocate(size_t fragments) {
  surface_ = gl::makeBuffer<float>(nullptr, fragments * 4);
  normal_ = gl::makeBuffer<float>(nullptr, fragments * 4);
  link_ = gl::makeBuffer<uint32_t>(nullptr, fragments * 2);
  capacity_ = fragments;
  gl::checkError("allocating fragment lists");
}

void FragmentLists::beginCollect(int width, int height) {
  const size_t pixels = size_t(width) * size_t(height);
  if (!header_.id()) {
    header_ = gl::makeBuffer<Header>(nullptr, 1, GL_DYNAMIC_STORAGE_BIT);
    fbo_ = gl::Framebuffer::create();
  }
  if (pixels > pixels_) heads_ = gl::makeBuffer<uint32_t>(nullptr, 2 * pixels), pixels_ = pixels;
  // A first guess of two fragments a pixel (the teacup and the bunny at
  // 640x480 have 0.7-0.8; 1080p at four would take 330 MB); check()
  // grows it to fit.
  if (capacity_ == 0) allocate(std::max<size_t>(2 * pixels, 1024));
  if (width != width_ || height != height_) {
    gl::NamedFramebufferParameteri(fbo_.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, width);
    gl::NamedFramebufferParameteri(fbo_.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, height);
    width_ = width, height_ = height;
  }
  const Header header{0, uint32_t(capacity_), width};
  gl::NamedBufferSubData(header_.id(), 0, sizeof header, &header);
  const uint32_t empty[2] = {0xffffffffu, 0};
  gl::ClearNamedBufferSubData(heads_.id(), GL_RG32UI, 0, GLsizeiptr(pixels * sizeof empty), GL_RG_INTEGER,
                              GL_UNSIGNED_INT, empty);
  bindForReading();
  fbo_.bind();
  gl::Viewport(0, 0, width, height);
}

FragmentLists::Fit FragmentLists::check() {
  gl::MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  uint32_t count = 0;
  header_.read(0, sizeof count, &count);
  if (count <= capacity_) return Fit::Fits;
  GLint64 largest = 0;
  gl::GetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &largest);
  // Room for a quarter more than this pass needed: the next view's
  // fragments differ a little.
  const size_t wanted = size_t(count) + size_t(count) / 4;
  if (wanted * kBytesPerFragment > gMaxBytes || wanted * 16 > size_t(largest) || count == 0xffffffffu)
    return Fit::TooLarge;
  allocate(wanted);
  return Fit::Grown;
}

void FragmentLists::bindForReading() const {
  header_.bindStorage(2);
  heads_.bindStorage(3);
  surface_.bindStorage(4);
  normal_.bindStorage(5);
  link_.bindStorage(6);
}

}  // namespace mvr
