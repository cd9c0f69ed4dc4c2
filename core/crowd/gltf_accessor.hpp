#pragma once
// Bounds-checked reads of glTF accessors (tinygltf's parser leaves most of these checks to the
// caller): every byte read is proven to lie inside its buffer view and buffer first, so a
// hostile file yields a LoadError instead of an out-of-bounds read. Sparse accessors are applied.

#include <tiny_gltf.h>

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

namespace tourmap::crowd::gltf {

// Where a failing read reports from: the file, used as LoadError::where().
struct ReadContext {
  const tinygltf::Model& model;
  const std::string& file;
};

struct FloatAccessor {
  std::size_t count = 0;
  int components = 0;         // 1 SCALAR, 2 VEC2, 3 VEC3, 4 VEC4, 16 MAT4 ...
  std::vector<float> values;  // count * components, element-major
  float at(std::size_t element, int component) const {
    return values[element * static_cast<std::size_t>(components) + static_cast<std::size_t>(component)];
  }
};

struct UintAccessor {
  std::size_t count = 0;
  int components = 0;
  std::vector<std::uint32_t> values;
  std::uint32_t at(std::size_t element, int component) const {
    return values[element * static_cast<std::size_t>(components) + static_cast<std::size_t>(component)];
  }
};

// Any component type; normalized integers map to [0,1] / [-1,1] as the glTF spec says.
// `what` names the data in error messages (e.g. "mesh 2 primitive 0 POSITION").
// `allowed_components` (e.g. {3}) rejects accessors of another element type.
FloatAccessor read_floats(const ReadContext& ctx, int accessor, const std::string& what,
                          std::initializer_list<int> allowed_components);

// Unsigned integer component types only (indices, JOINTS_n).
UintAccessor read_uints(const ReadContext& ctx, int accessor, const std::string& what,
                        std::initializer_list<int> allowed_components);

}  // namespace tourmap::crowd::gltf
