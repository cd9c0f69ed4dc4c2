#include "poi/serialize.hpp"

#include <zlib.h>

#include <bit>
#include <cstring>
#include <stdexcept>

namespace tourmap::poi {
namespace {

constexpr char kMagic[4] = {'T', 'M', 'C', 'T'};
constexpr std::size_t kHeaderBytes = 4 + 4 + 8 + 8 + 8 + 4 + 4;  // magic, version, 3 counts, root, crc
constexpr std::size_t kNodeBytes = 7 * 8 + 6 * 4;                // doubles: centre, bbox, worth; u32: the rest

// Little-endian fields at a cursor; memcpy on little-endian hosts (a tree is ~80 MB per 1M POIs).
template <typename U>
void store(char*& p, U v) {
  if constexpr (std::endian::native == std::endian::little) {
    std::memcpy(p, &v, sizeof v);
  } else {
    for (std::size_t i = 0; i < sizeof v; ++i) p[i] = static_cast<char>((v >> (8 * i)) & 0xff);
  }
  p += sizeof v;
}
void store_double(char*& p, double v) { store(p, std::bit_cast<std::uint64_t>(v)); }

template <typename U>
U load(const char*& p) {
  U v = 0;
  if constexpr (std::endian::native == std::endian::little) {
    std::memcpy(&v, p, sizeof v);
  } else {
    for (std::size_t i = 0; i < sizeof v; ++i)
      v |= static_cast<U>(static_cast<U>(static_cast<unsigned char>(p[i])) << (8 * i));
  }
  p += sizeof v;
  return v;
}
double load_double(const char*& p) { return std::bit_cast<double>(load<std::uint64_t>(p)); }

std::uint32_t crc(std::string_view bytes) {
  return static_cast<std::uint32_t>(
      crc32_z(crc32_z(0, nullptr, 0), reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()));
}

[[noreturn]] void fail(const std::string& what) { throw std::invalid_argument("cluster tree: " + what); }

}  // namespace

std::string serialize(const ClusterTree& t) {
  std::string out(kHeaderBytes + t.nodes.size() * kNodeBytes + t.children.size() * 4, '\0');
  char* p = out.data();
  std::memcpy(p, kMagic, 4);
  p += 4;
  store<std::uint32_t>(p, kClusterTreeFormat);
  store<std::uint64_t>(p, t.leaves);
  store<std::uint64_t>(p, t.nodes.size());
  store<std::uint64_t>(p, t.children.size());
  store<std::uint32_t>(p, t.root);
  char* checksum = p;
  p += 4;
  for (const ClusterNode& c : t.nodes) {
    for (double v : {c.center.x, c.center.y, c.min.x, c.min.y, c.max.x, c.max.y, c.worth}) store_double(p, v);
    for (std::uint32_t v :
         {c.size, c.representative, static_cast<std::uint32_t>(c.parent), c.first_child, c.child_count, c.level})
      store(p, v);
  }
  for (std::uint32_t c : t.children) store(p, c);
  store(checksum, crc(std::string_view(out).substr(kHeaderBytes)));
  return out;
}

ClusterTree deserialize(std::string_view bytes) {
  if (bytes.size() < kHeaderBytes) fail("truncated header");
  if (std::memcmp(bytes.data(), kMagic, 4) != 0) fail("bad magic");
  const char* p = bytes.data() + 4;
  const auto version = load<std::uint32_t>(p);
  if (version != kClusterTreeFormat) fail("unsupported format version " + std::to_string(version));
  const auto leaves = load<std::uint64_t>(p);
  const auto node_count = load<std::uint64_t>(p);
  const auto child_count = load<std::uint64_t>(p);
  const auto root = load<std::uint32_t>(p);
  const auto checksum = load<std::uint32_t>(p);

  const std::size_t body = bytes.size() - kHeaderBytes;
  if (node_count > body / kNodeBytes || child_count > body / 4 || node_count * kNodeBytes + child_count * 4 != body)
    fail("size does not match the header");
  if (crc(bytes.substr(kHeaderBytes)) != checksum) fail("checksum mismatch");
  if (leaves > node_count || node_count > 0x7fffffff ||
      (node_count > 0 && (root >= node_count || child_count != node_count - 1)) ||
      (node_count == 0 && child_count != 0))
    fail("inconsistent counts");

  ClusterTree t;
  t.leaves = leaves;
  t.root = root;
  // Room for incremental updates to add POIs without moving the array (poi/cluster_update.hpp);
  // pages that are never written cost no memory.
  t.nodes.reserve(node_count + node_count / 8);
  t.nodes.resize(node_count);
  for (ClusterNode& c : t.nodes) {
    for (double* v : {&c.center.x, &c.center.y, &c.min.x, &c.min.y, &c.max.x, &c.max.y, &c.worth}) *v = load_double(p);
    c.size = load<std::uint32_t>(p);
    c.representative = load<std::uint32_t>(p);
    c.parent = static_cast<std::int32_t>(load<std::uint32_t>(p));
    c.first_child = load<std::uint32_t>(p);
    c.child_count = load<std::uint32_t>(p);
    c.level = load<std::uint32_t>(p);
  }
  t.children.resize(child_count);
  for (std::uint32_t& c : t.children) c = load<std::uint32_t>(p);

  // Structure: every node but the root listed exactly once, by its parent, at a lower level;
  // leaves first and childless; representatives are leaves.
  std::vector<char> listed(node_count, 0);
  for (std::uint32_t id = 0; id < node_count; ++id) {
    const ClusterNode& c = t.nodes[id];
    if ((id < leaves) != (c.child_count == 0)) fail("leaf/inner node mismatch at node " + std::to_string(id));
    if (c.representative >= leaves) fail("representative out of range at node " + std::to_string(id));
    if (std::uint64_t{c.first_child} + c.child_count > child_count)
      fail("child range out of bounds at node " + std::to_string(id));
    for (std::uint32_t a = 0; a < c.child_count; ++a) {
      const std::uint32_t child = t.children[c.first_child + a];
      if (child >= node_count || listed[child] || t.nodes[child].parent != static_cast<std::int32_t>(id) ||
          t.nodes[child].level >= c.level)
        fail("bad child link at node " + std::to_string(id));
      listed[child] = 1;
    }
  }
  if (node_count > 0 && t.nodes[root].parent != -1) fail("root has a parent");
  return t;
}

}  // namespace tourmap::poi
