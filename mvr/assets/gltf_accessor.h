#pragma once
// One glTF accessor's elements, checked against its buffer once: up to
// four components each as floats (normalized integers scaled as the spec
// says), a MAT4 as a matrix, or unsigned indices. A sparse accessor's
// elements are its base's (or zeros) with its sparse values put in.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

namespace mvr::gltf {

class Accessor {
 public:
  // `where`: the file, for errors.
  Accessor(const tinygltf::Model& m, int index, const std::string& where);
  // Elements decoded elsewhere (a Draco-compressed primitive's): `count`
  // packed elements of `components` floats, or unsigned ints (indices).
  Accessor(std::vector<float> values, int components, const std::string& where);
  explicit Accessor(const std::vector<uint32_t>& indices, const std::string& where);

  size_t count() const { return count_; }
  int components() const { return components_; }

  glm::vec4 at(size_t k) const;
  glm::mat4 matrix(size_t k) const;  // a float MAT4's (column-major, as glTF's)
  uint32_t index(size_t k) const;

 private:
  void sparse(const tinygltf::Model& m, const tinygltf::Accessor& a, size_t element);
  float component(const unsigned char* p, int c) const;
  float scaled(float v, float max) const { return normalized_ ? v / max : v; }

  std::string where_;
  int type_ = 0, components_ = 0;
  bool normalized_ = false;
  size_t count_ = 0, stride_ = 0;
  const unsigned char* data_ = nullptr;
  std::vector<unsigned char> owned_;  // a sparse accessor's elements, packed
};

}  // namespace mvr::gltf
