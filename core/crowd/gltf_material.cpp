#include "crowd/gltf_material.hpp"

#include "load/load_error.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace tourmap::crowd::gltf {
namespace {

float srgb_to_linear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

float linear_to_srgb(float c) {
  c = std::clamp(c, 0.f, 1.f);
  return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1 / 2.4f) - 0.055f;
}

// The decoded image of the material's base colour texture, or null (no texture, or an image
// tinygltf could not decode: the factor alone is used then).
const tinygltf::Image* base_color_image(const ReadContext& ctx, const tinygltf::Material& mat) {
  const int tex = mat.pbrMetallicRoughness.baseColorTexture.index;
  const auto& m = ctx.model;
  if (tex < 0 || static_cast<std::size_t>(tex) >= m.textures.size()) return nullptr;
  const int src = m.textures[static_cast<std::size_t>(tex)].source;
  if (src < 0 || static_cast<std::size_t>(src) >= m.images.size()) return nullptr;
  const tinygltf::Image& img = m.images[static_cast<std::size_t>(src)];
  if (img.width <= 0 || img.height <= 0 || img.component < 1 || img.component > 4 || (img.bits != 8 && img.bits != 16))
    return nullptr;
  const std::size_t need = static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height) *
                           static_cast<std::size_t>(img.component) * static_cast<std::size_t>(img.bits / 8);
  return img.image.size() >= need ? &img : nullptr;
}

// Linear RGBA of the texel nearest to (u, v); glTF's UV origin is the image's top-left corner.
Eigen::Vector4f sample_nearest(const tinygltf::Image& img, float u, float v) {
  auto texel_index = [](float t, int size) {
    const float wrapped = t - std::floor(t);  // REPEAT
    return std::min(size - 1, static_cast<int>(wrapped * static_cast<float>(size)));
  };
  const std::size_t x = static_cast<std::size_t>(texel_index(u, img.width));
  const std::size_t y = static_cast<std::size_t>(texel_index(v, img.height));
  const std::size_t comps = static_cast<std::size_t>(img.component);
  const std::size_t bytes = static_cast<std::size_t>(img.bits / 8);
  const std::size_t base = (y * static_cast<std::size_t>(img.width) + x) * comps * bytes;
  auto channel = [&](std::size_t c) {
    if (bytes == 1) return img.image[base + c] / 255.f;
    const std::size_t at = base + c * 2;  // stb returns 16-bit samples in host order
    std::uint16_t s;
    std::memcpy(&s, &img.image[at], 2);
    return s / 65535.f;
  };
  Eigen::Vector4f rgba(1, 1, 1, 1);
  if (comps <= 2) {  // grey (+ alpha)
    rgba.head<3>().setConstant(srgb_to_linear(channel(0)));
  } else {
    for (std::size_t c = 0; c < 3; ++c) rgba[static_cast<int>(c)] = srgb_to_linear(channel(c));
  }
  return rgba;
}

}  // namespace

std::vector<std::array<std::uint8_t, 4>> primitive_colors(const ReadContext& ctx, const tinygltf::Primitive& primitive,
                                                          std::size_t vertex_count, const std::string& what) {
  Eigen::Vector4f factor(1, 1, 1, 1);
  const tinygltf::Image* image = nullptr;
  FloatAccessor uv;
  if (primitive.material >= 0 && static_cast<std::size_t>(primitive.material) < ctx.model.materials.size()) {
    const tinygltf::Material& mat = ctx.model.materials[static_cast<std::size_t>(primitive.material)];
    const auto& f = mat.pbrMetallicRoughness.baseColorFactor;
    if (f.size() == 4)
      for (int c = 0; c < 4; ++c)
        factor[c] =
            std::isfinite(f[static_cast<std::size_t>(c)]) ? static_cast<float>(f[static_cast<std::size_t>(c)]) : 1.f;
    image = base_color_image(ctx, mat);
    if (image) {
      const std::string attr = "TEXCOORD_" + std::to_string(mat.pbrMetallicRoughness.baseColorTexture.texCoord);
      const auto it = primitive.attributes.find(attr);
      if (it == primitive.attributes.end()) {
        image = nullptr;
      } else {
        uv = read_floats(ctx, it->second, what + " " + attr, {2});
        if (uv.count != vertex_count)
          throw load::LoadError(ctx.file, what + " " + attr + " count differs from POSITION");
      }
    }
  }
  FloatAccessor vertex_color;
  if (const auto it = primitive.attributes.find("COLOR_0"); it != primitive.attributes.end()) {
    vertex_color = read_floats(ctx, it->second, what + " COLOR_0", {3, 4});
    if (vertex_color.count != vertex_count)
      throw load::LoadError(ctx.file, what + " COLOR_0 count differs from POSITION");
  }

  std::vector<std::array<std::uint8_t, 4>> out(vertex_count);
  for (std::size_t v = 0; v < vertex_count; ++v) {
    Eigen::Vector4f c = factor;
    if (image) c = c.cwiseProduct(sample_nearest(*image, uv.at(v, 0), uv.at(v, 1)));
    if (vertex_color.count)
      for (int k = 0; k < 3; ++k) c[k] *= vertex_color.at(v, k);
    for (int k = 0; k < 3; ++k)
      out[v][static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(std::lround(255.f * linear_to_srgb(c[k])));
    out[v][3] = 255;
  }
  return out;
}

}  // namespace tourmap::crowd::gltf
