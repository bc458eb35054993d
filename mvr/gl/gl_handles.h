#pragma once
// Move-only owners of GL object names: one GL object, one small type.
#include <cstdint>
#include <initializer_list>
#include <iterator>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "mvr/gl/gl_api.h"

namespace mvr::gl {

// Self: the type that derives from it (Buffer, Program, ...), which
// create() makes.
template <class Traits, class Self>
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

  static Self create() { return Self(Traits::create()); }
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

class Shader : public Object<ShaderTraits, Shader> {
 public:
  using Object::Object;
};

// A buffer object and what is done with it: bound to an indexed target,
// read back, written, cleared.
class Buffer : public Object<BufferTraits, Buffer> {
 public:
  using Object::Object;
  // Binding `index` of the shader storage (or uniform) blocks.
  void bindStorage(GLuint index) const { BindBufferBase(GL_SHADER_STORAGE_BUFFER, index, id()); }
  void bindUniform(GLuint index) const { BindBufferBase(GL_UNIFORM_BUFFER, index, id()); }
  // `bytes` from `offset` into dst (waits for the GPU).
  void read(size_t offset, size_t bytes, void* dst) const {
    GetNamedBufferSubData(id(), GLintptr(offset), GLsizeiptr(bytes), dst);
  }
  template <class T>
  T value(size_t index = 0) const {
    T v{};
    read(index * sizeof(T), sizeof(T), &v);
    return v;
  }
  template <class T>
  std::vector<T> values(size_t count, size_t first = 0) const {
    std::vector<T> v(count);
    if (count) read(first * sizeof(T), count * sizeof(T), v.data());
    return v;
  }
  void write(size_t offset, size_t bytes, const void* src) const {
    NamedBufferSubData(id(), GLintptr(offset), GLsizeiptr(bytes), src);
  }
  // The first `count` 32-bit words set to `word`.
  void fill(size_t count, uint32_t word = 0) const {
    ClearNamedBufferSubData(id(), GL_R32UI, 0, GLsizeiptr(count * sizeof(uint32_t)), GL_RED_INTEGER, GL_UNSIGNED_INT,
                            &word);
  }
};

// A vertex array: its buffers and float attributes, bound for drawing.
class VertexArray : public Object<VertexArrayTraits, VertexArray> {
 public:
  using Object::Object;
  void bind() const { BindVertexArray(id()); }
  void vertexBuffer(GLuint buffer, GLsizei stride, GLuint binding = 0, GLintptr offset = 0) const {
    VertexArrayVertexBuffer(id(), binding, buffer, offset, stride);
  }
  void elementBuffer(GLuint buffer) const { VertexArrayElementBuffer(id(), buffer); }
  // Attribute `index`: `components` floats at `offset` bytes into a vertex
  // of `binding`, enabled.
  void attribute(GLuint index, GLint components, GLuint offset, GLuint binding = 0) const {
    VertexArrayAttribFormat(id(), index, components, GL_FLOAT, GL_FALSE, offset);
    VertexArrayAttribBinding(id(), index, binding);
    EnableVertexArrayAttrib(id(), index);
  }
};

// A framebuffer and its attachments.
class Framebuffer : public Object<FramebufferTraits, Framebuffer> {
 public:
  using Object::Object;
  void bind() const { BindFramebuffer(GL_FRAMEBUFFER, id()); }
  // texture 0 detaches.
  void attach(GLenum attachment, GLuint texture, GLint level = 0) const {
    NamedFramebufferTexture(id(), attachment, texture, level);
  }
  bool complete() const { return CheckNamedFramebufferStatus(id(), GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE; }
  void drawBuffers(std::initializer_list<GLenum> buffers) const {
    NamedFramebufferDrawBuffers(id(), GLsizei(buffers.size()), std::data(buffers));
  }
};

// A linked program: made current, and its uniforms' locations looked up
// once (gl_program.h sets them by name).
class Program : public Object<ProgramTraits, Program> {
 public:
  using Object::Object;
  void use() const { UseProgram(id()); }
  GLint location(const char* name) const {
    auto [at, added] = locations_.try_emplace(name, -1);
    if (added) at->second = GetUniformLocation(id(), name);
    return at->second;
  }

 private:
  mutable std::unordered_map<std::string, GLint> locations_;
};

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
  explicit operator bool() const { return id_ != 0; }
  // A 2D texture with one level: filtered by `filter`, clamped at edges.
  static Texture image2D(GLenum format, int width, int height, GLenum filter = GL_NEAREST) {
    Texture t(GL_TEXTURE_2D);
    TextureStorage2D(t.id(), 1, format, width, height);
    t.filter(filter, filter);
    t.wrap(GL_CLAMP_TO_EDGE);
    return t;
  }
  // A 2D array (or cube map array) with one level: `layers` of width x
  // height, bilinear, clamped at edges; fill it with uploadLayers.
  static Texture array2D(GLenum target, GLenum format, int width, int height, int layers) {
    Texture t(target);
    TextureStorage3D(t.id(), 1, format, width, height, layers);
    t.filter(GL_LINEAR, GL_LINEAR);
    t.wrap(GL_CLAMP_TO_EDGE);
    return t;
  }
  // `count` layers from `first`, width x height of tightly packed texels
  // (type GL_UNSIGNED_BYTE or GL_FLOAT) into the corner of each.
  void uploadLayers(int first, int count, int width, int height, GLenum format, GLenum type,
                    const void* texels) const {
    PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    TextureSubImage3D(id_, 0, 0, 0, first, width, height, count, format, type, texels);
  }
  // A buffer texture over `buffer` (texelFetch of a samplerBuffer).
  static Texture overBuffer(GLenum format, GLuint buffer) {
    Texture t(GL_TEXTURE_BUFFER);
    TextureBuffer(t.id(), format, buffer);
    return t;
  }
  void filter(GLenum min, GLenum mag) const {
    TextureParameteri(id_, GL_TEXTURE_MIN_FILTER, GLint(min));
    TextureParameteri(id_, GL_TEXTURE_MAG_FILTER, GLint(mag));
  }
  void wrap(GLenum mode) const {
    for (GLenum axis : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
      TextureParameteri(id_, axis, GLint(mode));
  }
  void bind(GLuint unit) const { BindTextureUnit(unit, id_); }
  void storage2D(GLenum format, int width, int height, int levels = 1) const {
    TextureStorage2D(id_, levels, format, width, height);
  }
  void reset() {
    if (id_) DeleteTextures(1, &id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

// Bindings by name, for objects another type owns (a slice table's
// buffers, a render target's texture).
inline void bindStorage(GLuint index, GLuint buffer) { BindBufferBase(GL_SHADER_STORAGE_BUFFER, index, buffer); }
inline void bindTexture(GLuint unit, GLuint texture) { BindTextureUnit(unit, texture); }
inline GLint getInteger(GLenum name) {
  GLint v = 0;
  GetIntegerv(name, &v);
  return v;
}

// A buffer filled once with immutable storage.
template <class T>
Buffer makeBuffer(const T* data, size_t count, GLbitfield flags = 0) {
  Buffer b = Buffer::create();
  NamedBufferStorage(b.id(), GLsizeiptr(count * sizeof(T) + (count == 0 ? 1 : 0)), data, flags);
  return b;
}

}  // namespace mvr::gl
