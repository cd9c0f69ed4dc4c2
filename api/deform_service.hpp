#pragma once
// The deformation engine behind POST /api/v1/deform/*: turns a validated request into targets
// on a prepared system, runs it, and answers with the deformed roads, the grid and stats.
//
// Three caches keep dragging interactive:
//   networks  - a road network in map units with its node lookups, per (id, version)
//   prepared  - grid + system + Cholesky factorization, per (network, grid, weights, boundary,
//               guide vertex set): a new focus scale or position, or new guide targets, re-use it
//   results   - whole response bodies, per (network, request)

#include "catalog.hpp"
#include "deform_request.hpp"
#include "lru_cache.hpp"
#include "single_flight.hpp"

#include "deform/applications.hpp"
#include "deform/deformer.hpp"

#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <unordered_set>

namespace tourmap::api {

struct DeformNetwork {
  std::string key;  // "<id>@<version>" or "inline:<hash>"
  std::shared_ptr<const RoadNetworkEntry> entry;
  deform::PlanarNetwork planar;
  std::vector<geo::LonLat> rest_lonlat;
  std::unordered_map<std::int64_t, std::uint32_t> node_by_id;
  std::unordered_set<std::uint64_t> edge_keys;  // undirected node-index pairs, for route checks
  std::unique_ptr<deform::NodeIndex> index;
  deform::FastUnproject unproject;  // map units -> lon/lat over the map and a 25% margin

  bool has_edge(std::uint32_t a, std::uint32_t b) const;
  std::size_t memory_bytes() const;    // approximate, for the cache budget (the shared entry excluded)
};

class DeformService {
 public:
  explicit DeformService(Catalog& catalog, DeformLimits limits = {});
  Response handle(DeformApp app, const Request& req);

  struct CacheStats {
    std::size_t networks, prepared, results, result_bytes;
    std::size_t network_bytes = 0, prepared_bytes = 0;  // as charged to the caches' budgets
  };
  CacheStats cache_stats() const;

 private:
  std::shared_ptr<const DeformNetwork> network_for(const DeformRequest& r);
  std::shared_ptr<deform::Prepared> prepared_for(const DeformRequest& r, const DeformNetwork& net,
                                                 const std::vector<std::uint32_t>& guide_nodes, bool* cache_hit,
                                                 std::string* key_out);
  std::shared_ptr<deform::Prepared> build_prepared(const DeformRequest& r, const DeformNetwork& net,
                                                   const std::vector<std::uint32_t>& guide_nodes) const;

  Catalog& catalog_;
  DeformLimits limits_;
  // Each bounded in bytes (DeformLimits): a prepared system of a fine grid holds hundreds of MB.
  LruCache<std::shared_ptr<const DeformNetwork>> networks_;
  LruCache<std::shared_ptr<deform::Prepared>> prepared_;
  LruCache<std::shared_ptr<const std::string>> results_;
  SingleFlight<std::shared_ptr<deform::Prepared>> building_;
};

}  // namespace tourmap::api
