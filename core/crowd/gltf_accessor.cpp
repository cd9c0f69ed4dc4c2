#include "crowd/gltf_accessor.hpp"

#include "load/load_error.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace tourmap::crowd::gltf {
namespace {

// More elements than any real character or room has; caps allocations driven by a header.
constexpr std::size_t kMaxElements = std::size_t{1} << 26;

[[noreturn]] void fail(const ReadContext& ctx, const std::string& what, const std::string& problem) {
  throw load::LoadError(ctx.file, what + ": " + problem);
}

int component_bytes(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

int element_components(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    case TINYGLTF_TYPE_MAT2:
      return 4;
    case TINYGLTF_TYPE_MAT3:
      return 9;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

double decode(const unsigned char* p, int component_type, bool normalized) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      std::int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      std::uint8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    default: {  // FLOAT (callers validated the type)
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

// The first byte of `count` elements of `element_bytes` each, `stride` apart, starting
// `offset` bytes into buffer view `view_index`, after proving the whole span is inside both
// the view and its buffer.
const unsigned char* checked_span(const ReadContext& ctx, int view_index, std::size_t offset, std::size_t count,
                                  std::size_t stride, std::size_t element_bytes, const std::string& what) {
  const auto& m = ctx.model;
  if (view_index < 0 || static_cast<std::size_t>(view_index) >= m.bufferViews.size())
    fail(ctx, what, "buffer view " + std::to_string(view_index) + " does not exist");
  const tinygltf::BufferView& view = m.bufferViews[static_cast<std::size_t>(view_index)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= m.buffers.size())
    fail(ctx, what, "buffer " + std::to_string(view.buffer) + " does not exist");
  const std::vector<unsigned char>& data = m.buffers[static_cast<std::size_t>(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
    fail(ctx, what,
         "buffer view " + std::to_string(view_index) + " exceeds its buffer (" + std::to_string(data.size()) +
             " bytes)");
  if (count == 0) return data.data();
  // count <= kMaxElements and stride <= 255 + 16*4, so none of these products overflow.
  const std::size_t span = (count - 1) * stride + element_bytes;
  if (offset > view.byteLength || span > view.byteLength - offset)
    fail(ctx, what,
         std::to_string(count) + " elements of " + std::to_string(element_bytes) + " bytes at offset " +
             std::to_string(offset) + " exceed buffer view " + std::to_string(view_index) + " (" +
             std::to_string(view.byteLength) + " bytes)");
  return data.data() + view.byteOffset + offset;
}

struct RawAccessor {
  std::size_t count = 0;
  int components = 0;
  int component_type = 0;
  bool normalized = false;
  std::vector<double> values;
};

RawAccessor read_raw(const ReadContext& ctx, int accessor_index, const std::string& what,
                     std::initializer_list<int> allowed_components) {
  const auto& m = ctx.model;
  if (accessor_index < 0 || static_cast<std::size_t>(accessor_index) >= m.accessors.size())
    fail(ctx, what, "accessor " + std::to_string(accessor_index) + " does not exist");
  const tinygltf::Accessor& acc = m.accessors[static_cast<std::size_t>(accessor_index)];
  RawAccessor out;
  out.components = element_components(acc.type);
  out.component_type = acc.componentType;
  out.normalized = acc.normalized;
  const int cbytes = component_bytes(acc.componentType);
  if (out.components == 0 || cbytes == 0)
    fail(ctx, what, "accessor " + std::to_string(accessor_index) + " has an invalid type");
  if (std::find(allowed_components.begin(), allowed_components.end(), out.components) == allowed_components.end())
    fail(ctx, what,
         "accessor " + std::to_string(accessor_index) + " has " + std::to_string(out.components) +
             " components per element, which is not expected here");
  // Matrices of 1- or 2-byte components have column padding; no model we load uses them.
  if (acc.type >= TINYGLTF_TYPE_MAT2 && acc.type <= TINYGLTF_TYPE_MAT4 && cbytes != 4)
    fail(ctx, what, "matrix accessors with 8/16-bit components are not supported");
  if (acc.count > kMaxElements)
    fail(ctx, what,
         "accessor " + std::to_string(accessor_index) + " has " + std::to_string(acc.count) +
             " elements, more than the limit " + std::to_string(kMaxElements));
  out.count = acc.count;
  const std::size_t comps = static_cast<std::size_t>(out.components);
  const std::size_t element_bytes = comps * static_cast<std::size_t>(cbytes);
  out.values.assign(out.count * comps, 0.0);  // an accessor without a buffer view is zeros

  if (acc.bufferView >= 0) {
    if (static_cast<std::size_t>(acc.bufferView) >= m.bufferViews.size())
      fail(ctx, what, "buffer view " + std::to_string(acc.bufferView) + " does not exist");
    const tinygltf::BufferView& view = m.bufferViews[static_cast<std::size_t>(acc.bufferView)];
    const std::size_t stride = view.byteStride == 0 ? element_bytes : view.byteStride;
    if (stride < element_bytes || stride > 252 + element_bytes)
      fail(ctx, what,
           "byte stride " + std::to_string(stride) + " does not fit elements of " + std::to_string(element_bytes) +
               " bytes");
    const unsigned char* base =
        checked_span(ctx, acc.bufferView, acc.byteOffset, out.count, stride, element_bytes, what);
    for (std::size_t e = 0; e < out.count; ++e)
      for (std::size_t c = 0; c < comps; ++c)
        out.values[e * comps + c] =
            decode(base + e * stride + c * static_cast<std::size_t>(cbytes), acc.componentType, acc.normalized);
  }

  if (acc.sparse.isSparse) {
    const std::size_t n = acc.sparse.count < 0 ? kMaxElements + 1 : static_cast<std::size_t>(acc.sparse.count);
    if (n > out.count) fail(ctx, what, "sparse count exceeds the accessor count");
    const int itype = acc.sparse.indices.componentType;
    const int ibytes = component_bytes(itype);
    if (itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      fail(ctx, what, "sparse indices must be unsigned integers");
    if (acc.sparse.indices.byteOffset < 0 || acc.sparse.values.byteOffset < 0)
      fail(ctx, what, "negative sparse byte offset");
    const unsigned char* idx =
        checked_span(ctx, acc.sparse.indices.bufferView, static_cast<std::size_t>(acc.sparse.indices.byteOffset), n,
                     static_cast<std::size_t>(ibytes), static_cast<std::size_t>(ibytes), what);
    const unsigned char* val =
        checked_span(ctx, acc.sparse.values.bufferView, static_cast<std::size_t>(acc.sparse.values.byteOffset), n,
                     element_bytes, element_bytes, what);
    for (std::size_t s = 0; s < n; ++s) {
      const double target = decode(idx + s * static_cast<std::size_t>(ibytes), itype, false);
      if (target >= static_cast<double>(out.count)) fail(ctx, what, "sparse index out of range");
      const std::size_t e = static_cast<std::size_t>(target);
      for (std::size_t c = 0; c < comps; ++c)
        out.values[e * comps + c] =
            decode(val + s * element_bytes + c * static_cast<std::size_t>(cbytes), acc.componentType, acc.normalized);
    }
  }
  return out;
}

}  // namespace

FloatAccessor read_floats(const ReadContext& ctx, int accessor, const std::string& what,
                          std::initializer_list<int> allowed_components) {
  RawAccessor raw = read_raw(ctx, accessor, what, allowed_components);
  FloatAccessor out;
  out.count = raw.count;
  out.components = raw.components;
  out.values.resize(raw.values.size());
  for (std::size_t i = 0; i < raw.values.size(); ++i) {
    if (!std::isfinite(raw.values[i]))
      fail(ctx, what, "non-finite value at element " + std::to_string(i / static_cast<std::size_t>(raw.components)));
    out.values[i] = static_cast<float>(raw.values[i]);
  }
  return out;
}

UintAccessor read_uints(const ReadContext& ctx, int accessor, const std::string& what,
                        std::initializer_list<int> allowed_components) {
  RawAccessor raw = read_raw(ctx, accessor, what, allowed_components);
  if (raw.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      raw.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      raw.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    fail(ctx, what, "expected unsigned integer components");
  UintAccessor out;
  out.count = raw.count;
  out.components = raw.components;
  out.values.resize(raw.values.size());
  for (std::size_t i = 0; i < raw.values.size(); ++i) out.values[i] = static_cast<std::uint32_t>(raw.values[i]);
  return out;
}

}  // namespace tourmap::crowd::gltf
