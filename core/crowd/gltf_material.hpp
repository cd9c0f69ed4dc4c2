#pragma once
// Per-vertex base colour of a glTF primitive: material baseColorFactor x base colour texture
// (nearest texel at the vertex UV, REPEAT wrapping) x COLOR_0, as the glTF spec combines them,
// computed in linear space and stored sRGB-encoded 8-bit (what a plain framebuffer displays).

#include "crowd/gltf_accessor.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tourmap::crowd::gltf {

// One RGBA colour per vertex of `primitive` (vertex_count of them). Alpha is 255.
std::vector<std::array<std::uint8_t, 4>> primitive_colors(const ReadContext& ctx, const tinygltf::Primitive& primitive,
                                                          std::size_t vertex_count, const std::string& what);

}  // namespace tourmap::crowd::gltf
