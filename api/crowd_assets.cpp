#include "crowd_assets.hpp"

#include "crowd/gltf_loader.hpp"
#include "crowd/hierarchy_build.hpp"
#include "crowd/hierarchy_io.hpp"
#include "crowd/subdivide.hpp"
#include "load/file.hpp"
#include "store/repo.hpp"
#include "util/elapsed.hpp"
#include "util/hash.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <sstream>

namespace tourmap::api {
namespace {

constexpr int kHierarchyFormat = 2;  // bump when the builder's output changes (2: measured error radii)

using util::ms_since;

// The model file's content hash: a changed file never reuses a cached hierarchy.
std::string file_hash(const std::string& path) {
  try {
    return util::hex64(util::fnv1a64(load::read_file(path)));
  } catch (const std::exception&) {
    throw std::runtime_error(path + ": cannot open the model file");
  }
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return s;
}

// Keeps only the animation the scene plays (case-insensitive substring of its name; the first
// if none matches), so bounds and simplification consider the poses that are shown.
void keep_animation(crowd::SkinnedModel& m, const std::string& wanted) {
  if (m.animations.empty()) throw std::runtime_error(m.name + ": has no animation");
  std::size_t pick = 0;
  if (!wanted.empty())
    for (std::size_t i = 0; i < m.animations.size(); ++i)
      if (lower(m.animations[i].name).find(lower(wanted)) != std::string::npos) {
        pick = i;
        break;
      }
  crowd::Animation a = std::move(m.animations[pick]);
  m.animations.clear();
  m.animations.push_back(std::move(a));
}

crowd::Affine normalizer(const crowd::SkinnedModel& m, float height_m) {
  const crowd::Box3 b = crowd::posed_bounds(m);
  const float h = std::max(b.sizes().y(), 1e-6f);
  const float s = height_m / h;
  const crowd::Vec3 foot(b.center().x(), b.min().y(), b.center().z());
  crowd::Affine a = crowd::Affine::Identity();
  a.scale(s);
  a.translate(-foot);
  return a;
}

}  // namespace

std::string crowd_character_key(const crowd::SceneCharacter& c) {
  return c.file + "|sub" + std::to_string(c.subdivision) + "|" + c.animation;
}

std::shared_ptr<const CrowdCharacter> CrowdAssets::load(const crowd::SceneCharacter& c, const CrowdProgress& progress,
                                                        int done, int total) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string path = models_dir_ + "/" + c.file;
  if (progress) progress("loading model", c.name, done, total);
  auto out = std::make_shared<CrowdCharacter>();
  out->name = c.name;
  crowd::SkinnedModel m = crowd::load_skinned_model(path);
  keep_animation(m, c.animation);
  if (c.subdivision > 0) m = crowd::subdivide(m, c.subdivision);
  m.name = c.name;
  out->normalize = normalizer(m, c.height_m);
  out->load_ms = ms_since(t0);

  const crowd::HierarchyOptions options;
  const std::string key = "crowd-hierarchy:v" + std::to_string(kHierarchyFormat) + ":" + file_hash(path) + ":" +
                          crowd_character_key(c) + ":s" + std::to_string(options.max_leaf_triangles) + ":d" +
                          std::to_string(options.pose_distance_fraction);
  if (db_) {
    try {
      auto db = db_->acquire();
      if (auto hit = store::cache_get(*db, key)) {
        out->hierarchy = crowd::deserialize_hierarchy(hit->body, m.vertex_count());
        out->from_cache = true;
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "crowd: cached hierarchy of %s unusable (%s); rebuilding\n", c.name.c_str(), e.what());
    }
  }
  if (!out->from_cache) {
    if (progress) progress("building hierarchy", c.name, done, total);
    const auto t1 = std::chrono::steady_clock::now();
    out->hierarchy = crowd::build_vdr_hierarchy(m, options);
    out->build_ms = ms_since(t1);
    if (db_) {
      try {
        auto db = db_->acquire();
        store::cache_put(*db, key, "crowd-hierarchy", {"application/octet-stream", crowd::serialize_hierarchy(out->hierarchy)});
      } catch (const std::exception& e) {
        std::fprintf(stderr, "crowd: cannot cache the hierarchy of %s: %s\n", c.name.c_str(), e.what());
      }
    }
  }
  out->model = std::move(m);
  return out;
}

crowd::SceneCharacter CrowdAssets::effective(const crowd::SceneCharacter& c) const {
  crowd::SceneCharacter e = c;
  if (max_subdivision_ >= 0) e.subdivision = std::min(e.subdivision, max_subdivision_);
  return e;
}

std::vector<std::shared_ptr<const CrowdCharacter>> CrowdAssets::characters(const crowd::SceneSpec& spec,
                                                                          const CrowdProgress& progress) {
  std::vector<std::shared_ptr<const CrowdCharacter>> out;
  const int total = static_cast<int>(spec.characters.size());
  for (int i = 0; i < total; ++i) {
    const crowd::SceneCharacter c = effective(spec.characters[static_cast<std::size_t>(i)]);
    const std::string key = crowd_character_key(c);
    {
      std::lock_guard lock(mutex_);
      if (auto it = loaded_.find(key); it != loaded_.end()) {
        out.push_back(it->second);
        continue;
      }
    }
    std::lock_guard build(build_mutex_);
    {
      std::lock_guard lock(mutex_);  // somebody else may have built it meanwhile
      if (auto it = loaded_.find(key); it != loaded_.end()) {
        out.push_back(it->second);
        continue;
      }
    }
    auto ch = load(c, progress, i, total);
    std::lock_guard lock(mutex_);
    loaded_[key] = ch;
    out.push_back(ch);
  }
  return out;
}

long long CrowdAssets::full_triangles(const crowd::SceneSpec& spec, int count) const {
  std::vector<long long> per_character;
  {
    std::lock_guard lock(mutex_);
    for (const auto& c : spec.characters) {
      auto it = loaded_.find(crowd_character_key(effective(c)));
      if (it == loaded_.end()) return -1;
      per_character.push_back(static_cast<long long>(it->second->model.triangle_count()));
    }
  }
  long long sum = 0;
  for (const auto& agent : crowd::build_scene(spec, count).agents) sum += per_character[static_cast<std::size_t>(agent.character)];
  return sum;
}

}  // namespace tourmap::api
