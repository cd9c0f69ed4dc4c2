#include "cut_instances.hpp"

#include <algorithm>
#include <atomic>

namespace tourmap::crowd {

void cut_instances(std::span<const CutInstance> instances, const CameraView& view, float poe, util::ForkJoin* pool,
                   CutWorkspace& workspace, std::vector<int>& cut, std::vector<std::size_t>& cut_begin, CutStats& stats) {
  const CutFrame frame = make_cut_frame(view, poe);
  const std::size_t n = instances.size();
  cut.clear();
  cut_begin.assign(n + 1, 0);
  stats = {};
  if (!pool || pool->threads() == 1 || n <= kCutChunk) {
    for (std::size_t i = 0; i < n; ++i) {
      lod_cut(*instances[i].tree, *instances[i].world, frame, cut, stats);
      cut_begin[i + 1] = cut.size();
    }
    return;
  }
  // Threads take chunks in turn (balanced whatever the cost per instance); each chunk has its
  // own output, concatenated below in chunk order, so the result is the single-threaded one.
  const std::size_t chunk_count = (n + kCutChunk - 1) / kCutChunk;
  if (workspace.chunks.size() < chunk_count) workspace.chunks.resize(chunk_count);
  std::atomic<std::size_t> next{0};
  pool->run([&](int) {
    for (std::size_t k; (k = next.fetch_add(1, std::memory_order_relaxed)) < chunk_count;) {
      CutWorkspace::Chunk& chunk = workspace.chunks[k];
      chunk.clusters.clear();
      chunk.counts.clear();
      chunk.stats = {};
      const std::size_t end = std::min(n, (k + 1) * kCutChunk);
      for (std::size_t i = k * kCutChunk; i < end; ++i) {
        const std::size_t before = chunk.clusters.size();
        lod_cut(*instances[i].tree, *instances[i].world, frame, chunk.clusters, chunk.stats);
        chunk.counts.push_back(static_cast<std::uint32_t>(chunk.clusters.size() - before));
      }
    }
  });
  std::size_t total = 0;
  for (std::size_t k = 0; k < chunk_count; ++k) total += workspace.chunks[k].clusters.size();
  cut.reserve(total);
  std::size_t i = 0;
  for (std::size_t k = 0; k < chunk_count; ++k) {
    const CutWorkspace::Chunk& chunk = workspace.chunks[k];
    cut.insert(cut.end(), chunk.clusters.begin(), chunk.clusters.end());
    for (std::uint32_t c : chunk.counts) {
      cut_begin[i + 1] = cut_begin[i] + c;
      ++i;
    }
    stats += chunk.stats;
  }
}

}  // namespace tourmap::crowd
