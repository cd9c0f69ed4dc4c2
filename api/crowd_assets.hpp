#pragma once
// The crowd characters a scene needs, loaded once: glTF model, Loop-subdivided to the scene's
// resolution, reduced to the animation the scene plays, and its VDR-AM cluster hierarchy. A
// hierarchy takes seconds to build, so it is cached in the store (result_cache, keyed by the
// model file's content hash and the build parameters) and survives restarts.

#include "crowd/cluster_hierarchy.hpp"
#include "crowd/scene.hpp"
#include "crowd/skinned_model.hpp"
#include "store/db_pool.hpp"

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace tourmap::api {

struct CrowdCharacter {
  std::string name;
  crowd::SkinnedModel model;          // one animation: the one the scene plays
  crowd::ClusterHierarchy hierarchy;
  crowd::Affine normalize;            // model -> feet at the origin, scaled to the scene's height
  bool from_cache = false;
  double load_ms = 0, build_ms = 0;
};

using CrowdProgress = std::function<void(const std::string& stage, const std::string& model, int done, int total)>;

class CrowdAssets {
 public:
  // models_dir: the data directory's models/ folder. db may be null (no persistent cache).
  // max_subdivision caps the scenes' Loop levels (-1: no cap).
  CrowdAssets(std::string models_dir, store::DbPool* db, int max_subdivision = -1)
      : models_dir_(std::move(models_dir)), db_(db), max_subdivision_(max_subdivision) {}

  // The characters of `spec`, in its order; loads and builds what is missing. Thread-safe;
  // throws std::runtime_error (naming the model file) when a model cannot be loaded.
  std::vector<std::shared_ptr<const CrowdCharacter>> characters(const crowd::SceneSpec& spec, const CrowdProgress& progress);

  // Full-resolution triangles of `count` characters of `spec`, or -1 if a model is not loaded yet.
  long long full_triangles(const crowd::SceneSpec& spec, int count) const;

 private:
  crowd::SceneCharacter effective(const crowd::SceneCharacter& c) const;
  std::shared_ptr<const CrowdCharacter> load(const crowd::SceneCharacter& c, const CrowdProgress& progress, int done,
                                             int total);

  std::string models_dir_;
  store::DbPool* db_;
  int max_subdivision_;
  mutable std::mutex mutex_;
  std::mutex build_mutex_;  // one build at a time
  std::map<std::string, std::shared_ptr<const CrowdCharacter>> loaded_;  // by character key
};

// Key of a built character: file, subdivision level, animation (the cache key adds the file hash).
std::string crowd_character_key(const crowd::SceneCharacter& c);

}  // namespace tourmap::api
