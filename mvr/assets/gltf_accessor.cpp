#include "mvr/assets/gltf_accessor.h"

#include <algorithm>
#include <cstring>

#include "mvr/error.h"

namespace mvr::gltf {
namespace {

size_t componentBytes(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

template <class T>
T read(const unsigned char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// The start of `count` elements of `element` bytes at `offset` into a
// buffer view, checked to lie inside it; stride: the view's, or packed.
const unsigned char* viewElements(const tinygltf::Model& m, int view, size_t offset, size_t count, size_t element,
                                  size_t& stride, const std::string& where, const std::string& what) {
  if (view < 0 || size_t(view) >= m.bufferViews.size()) fail(where, "buffer view " + std::to_string(view) + " does not exist");
  const tinygltf::BufferView& v = m.bufferViews[size_t(view)];
  if (v.buffer < 0 || size_t(v.buffer) >= m.buffers.size()) fail(where, "buffer " + std::to_string(v.buffer) + " does not exist");
  const std::vector<unsigned char>& data = m.buffers[size_t(v.buffer)].data;
  stride = v.byteStride ? v.byteStride : element;
  if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset ||
      (count && (offset > v.byteLength || (count - 1) > (v.byteLength - offset) / stride ||
                 (count - 1) * stride + element > v.byteLength - offset)))
    fail(where, what + " reaches past its buffer");
  return data.data() + v.byteOffset + offset;
}

}  // namespace

Accessor::Accessor(const tinygltf::Model& m, int index, const std::string& where) : where_(where) {
  const std::string name = "accessor " + std::to_string(index);
  if (index < 0 || size_t(index) >= m.accessors.size()) fail(where, name + " does not exist");
  const tinygltf::Accessor& a = m.accessors[size_t(index)];
  type_ = a.componentType, normalized_ = a.normalized, count_ = a.count;
  components_ = a.type == TINYGLTF_TYPE_SCALAR ? 1 : a.type == TINYGLTF_TYPE_VEC2 ? 2
                : a.type == TINYGLTF_TYPE_VEC3 ? 3 : a.type == TINYGLTF_TYPE_VEC4 ? 4
                : a.type == TINYGLTF_TYPE_MAT4 ? 16 : 0;
  const size_t bytes = componentBytes(type_);
  if (!components_ || !bytes) fail(where, name + " has a type we do not read");
  const size_t element = bytes * size_t(components_);
  if (a.bufferView >= 0) data_ = viewElements(m, a.bufferView, a.byteOffset, count_, element, stride_, where, name);
  if (a.sparse.isSparse) sparse(m, a, element);
}

Accessor::Accessor(std::vector<float> values, int components, const std::string& where)
    : where_(where), type_(TINYGLTF_COMPONENT_TYPE_FLOAT), components_(components) {
  count_ = components > 0 ? values.size() / size_t(components) : 0;
  stride_ = 4 * size_t(components);
  owned_.resize(values.size() * 4);
  std::memcpy(owned_.data(), values.data(), owned_.size());
  data_ = owned_.data();
}

Accessor::Accessor(const std::vector<uint32_t>& indices, const std::string& where)
    : where_(where), type_(TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT), components_(1), count_(indices.size()), stride_(4) {
  owned_.resize(indices.size() * 4);
  std::memcpy(owned_.data(), indices.data(), owned_.size());
  data_ = owned_.data();
}

// The base's elements (zeros without one) copied packed, then each sparse
// index's element replaced by its value (glTF 2.0, 3.6.2.3).
void Accessor::sparse(const tinygltf::Model& m, const tinygltf::Accessor& a, size_t element) {
  const std::string name = "a sparse accessor";
  if (count_ > (size_t(1) << 28)) fail(where_, name + " of more than 2^28 elements");
  owned_.assign(count_ * element, 0);
  if (data_)
    for (size_t k = 0; k < count_; ++k) std::memcpy(&owned_[k * element], data_ + k * stride_, element);
  const size_t n = a.sparse.count > 0 ? size_t(a.sparse.count) : 0;
  const int indexType = a.sparse.indices.componentType;
  const size_t indexBytes = componentBytes(indexType);
  if (a.sparse.count < 1 || n > count_ || indexType == TINYGLTF_COMPONENT_TYPE_BYTE || indexType == TINYGLTF_COMPONENT_TYPE_SHORT ||
      indexType == TINYGLTF_COMPONENT_TYPE_FLOAT || !indexBytes)
    fail(where_, name + " has a bad count or index type");
  size_t indexStride = 0, valueStride = 0;
  const unsigned char* indices = viewElements(m, a.sparse.indices.bufferView, size_t(std::max(a.sparse.indices.byteOffset, 0)), n,
                                              indexBytes, indexStride, where_, name + "'s indices");
  const unsigned char* values = viewElements(m, a.sparse.values.bufferView, size_t(std::max(a.sparse.values.byteOffset, 0)), n,
                                             element, valueStride, where_, name + "'s values");
  size_t previous = 0;
  for (size_t i = 0; i < n; ++i) {
    const unsigned char* p = indices + i * indexBytes;  // indices and values are packed (the spec)
    const size_t k = indexBytes == 1 ? *p : indexBytes == 2 ? read<uint16_t>(p) : read<uint32_t>(p);
    if (k >= count_ || (i > 0 && k <= previous)) fail(where_, name + "'s indices must rise and lie inside it");
    std::memcpy(&owned_[k * element], values + i * element, element);
    previous = k;
  }
  data_ = owned_.data(), stride_ = element;
}

glm::vec4 Accessor::at(size_t k) const {
  glm::vec4 out(0.0f);
  if (!data_) return out;
  const unsigned char* p = data_ + k * stride_;
  for (int c = 0; c < std::min(components_, 4); ++c) out[c] = component(p, c);
  return out;
}

glm::mat4 Accessor::matrix(size_t k) const {
  if (components_ != 16 || type_ != TINYGLTF_COMPONENT_TYPE_FLOAT) fail(where_, "a matrix accessor must be float MAT4");
  glm::mat4 m(1.0f);
  if (data_)
    for (int c = 0; c < 16; ++c) m[c / 4][c % 4] = component(data_ + k * stride_, c);
  return m;
}

uint32_t Accessor::index(size_t k) const {
  if (!data_) return 0;
  const unsigned char* p = data_ + k * stride_;
  switch (type_) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return read<uint16_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return read<uint32_t>(p);
    default: fail(where_, "indices must be unsigned integers");
  }
}

float Accessor::component(const unsigned char* p, int c) const {
  switch (type_) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return read<float>(p + 4 * c);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return scaled(float(p[c]), 255.0f);
    case TINYGLTF_COMPONENT_TYPE_BYTE: return std::max(scaled(float(int8_t(p[c])), 127.0f), -1.0f);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return scaled(float(read<uint16_t>(p + 2 * c)), 65535.0f);
    case TINYGLTF_COMPONENT_TYPE_SHORT: return std::max(scaled(float(read<int16_t>(p + 2 * c)), 32767.0f), -1.0f);
    default: return float(read<uint32_t>(p + 4 * c));
  }
}

}  // namespace mvr::gltf
