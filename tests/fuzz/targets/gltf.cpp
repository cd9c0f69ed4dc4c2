// glTF model loading (core/crowd/gltf_loader: load_skinned_model, as the crowd assets call it,
// and load_static_model) on a file rewritten for every input. Built twice: fuzz_gltf_glb
// writes model.glb (binary glTF), fuzz_gltf_json writes model.gltf (JSON, buffers as data:
// URIs); the loader picks the parser from the content. Sampling at 4 fps keeps long clips
// cheap. Clean error: load::LoadError ("Throws tourmap::load::LoadError naming the file and
// the problem on any bad input").

#include "fuzz_common.hpp"

#include "crowd/gltf_loader.hpp"
#include "load/load_error.hpp"

#ifndef TOURMAP_FUZZ_GLTF_FILE
#error "define TOURMAP_FUZZ_GLTF_FILE (model.glb or model.gltf)"
#endif

namespace {

void check(const tourmap::crowd::SkinnedModel& m) {
  const std::size_t n = m.positions.size();
  FUZZ_CHECK(!m.indices.empty() && m.indices.size() % 3 == 0);
  for (auto i : m.indices)
    FUZZ_CHECK(i < n);
  FUZZ_CHECK(m.normals.size() == n && m.joints.size() == n && m.weights.size() == n);
  const std::size_t joints = m.skeleton.parent.size();
  for (std::size_t v = 0; v < n; ++v)
    for (int k = 0; k < 4; ++k)
      FUZZ_CHECK(!(m.weights[v][k] > 0) || m.joints[v][k] < joints);
  FUZZ_CHECK(!m.animations.empty());
  for (const auto& a : m.animations)
    for (const auto& p : a.poses)
      FUZZ_CHECK(p.skinning.size() == m.skeleton.parent.size());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tourmap;
  const std::string path = fuzz::ScratchDir::get().write(TOURMAP_FUZZ_GLTF_FILE, fuzz::as_view(data, size));
  crowd::LoadOptions options;
  options.sample_fps = 4;
  try {
    check(crowd::load_skinned_model(path, options));
  } catch (const load::LoadError&) {
  }
  try {
    check(crowd::load_static_model(path, options));
  } catch (const load::LoadError&) {
  }
  return 0;
}
