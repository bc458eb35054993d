#pragma once
// Move-only owners of GL object names: one GL object, one small type.
#include <utility>

#include "mvr/gl/gl_api.h"

namespace mvr::gl {

template <class Traits>
class Object {
 public:
  Object() = default;
  explicit Object(GLuint id) : id_(id) {}
  ~Object() { reset(); }
  Object(Object&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  Object& operator=(Object&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;

  static Object create() { return Object(Traits::create()); }
  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_) Traits::destroy(id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

struct BufferTraits {
  static GLuint create() { GLuint id = 0; CreateBuffers(1, &id); return id; }
  static void destroy(GLuint id) { DeleteBuffers(1, &id); }
};
struct VertexArrayTraits {
  static GLuint create() { GLuint id = 0; CreateVertexArrays(1, &id); return id; }
  static void destroy(GLuint id) { DeleteVertexArrays(1, &id); }
};
struct FramebufferTraits {
  static GLuint create() { GLuint id = 0; CreateFramebuffers(1, &id); return id; }
  static void destroy(GLuint id) { DeleteFramebuffers(1, &id); }
};
struct ProgramTraits {
  static GLuint create() { return CreateProgram(); }
  static void destroy(GLuint id) { DeleteProgram(id); }
};
struct ShaderTraits {
  static void destroy(GLuint id) { DeleteShader(id); }
};

using Buffer = Object<BufferTraits>;
using VertexArray = Object<VertexArrayTraits>;
using Framebuffer = Object<FramebufferTraits>;
using Program = Object<ProgramTraits>;
using Shader = Object<ShaderTraits>;

// Textures need their target at creation.
class Texture {
 public:
  Texture() = default;
  explicit Texture(GLenum target) { CreateTextures(target, 1, &id_); }
  ~Texture() { reset(); }
  Texture(Texture&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  Texture& operator=(Texture&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  Texture(const Texture&) = delete;
  Texture& operator=(const Texture&) = delete;
  GLuint id() const { return id_; }
  void reset() {
    if (id_) DeleteTextures(1, &id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

// A buffer filled once with immutable storage.
template <class T>
Buffer makeBuffer(const T* data, size_t count, GLbitfield flags = 0) {
  Buffer b = Buffer::create();
  NamedBufferStorage(b.id(), GLsizeiptr(count * sizeof(T) + (count == 0 ? 1 : 0)), data, flags);
  return b;
}

}  // namespace mvr::gl
