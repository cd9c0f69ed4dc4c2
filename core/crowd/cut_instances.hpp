#pragma once
// The LOD cut (sec. 3.5.1) of every instance of a frame, optionally split over a ForkJoin pool.
// The result does not depend on the thread count: instance i's cut is the one lod_cut gives,
// stored at [cut_begin[i], cut_begin[i + 1]) of `cut`, and the stats are the sums over instances.

#include "cut_tree.hpp"
#include "lod_cut.hpp"
#include "util/fork_join.hpp"

#include <span>
#include <vector>

namespace tourmap::crowd {

struct CutInstance {
  const CutTree* tree = nullptr;
  const Affine* world = nullptr;  // model -> world, rigid with uniform scale
};

// Per-thread scratch kept between frames (chunks of instances cut by whichever thread takes them).
struct CutWorkspace {
  struct Chunk {
    std::vector<int> clusters;
    std::vector<std::uint32_t> counts;  // clusters per instance of the chunk
    CutStats stats;
  };
  std::vector<Chunk> chunks;
};

// Instances per chunk of the multi-threaded split: small enough to balance two threads when
// culled instances (cheap) and near ones (deep cuts) come in runs.
inline constexpr std::size_t kCutChunk = 16;

// Replaces `cut`, `cut_begin` (size n + 1) and `stats` with the cuts of `instances` seen through
// `view` at `poe` (<= 0: NoLOD). `pool` may be null (this thread only).
void cut_instances(std::span<const CutInstance> instances, const CameraView& view, float poe, util::ForkJoin* pool,
                   CutWorkspace& workspace, std::vector<int>& cut, std::vector<std::size_t>& cut_begin, CutStats& stats);

}  // namespace tourmap::crowd
