#pragma once
// The metro map endpoints (paper ch. 5): layouts, visual worth rasters and active POI clusters,
// with their caches: per city version the derived data and the geographic cluster tree; per
// (city version, parameters) the layout (also persisted in the store's result cache, since a
// large network takes seconds) and the layout-space cluster tree.

#include "catalog.hpp"
#include "http.hpp"
#include "lru_cache.hpp"
#include "metro_layout.hpp"
#include "single_flight.hpp"

#include "poi/cluster_tree.hpp"

#include <memory>

namespace tourmap::api {

struct MetroLimits {
  std::size_t max_raster_side = 512;
  std::size_t max_m = 100;
  // Layouts (and layout-space clusters) of networks with more edges are refused (413): the
  // fast path's crossing tables grow with the square of the edges. The largest sample network
  // has 349 (London); a regional rail network a few thousand.
  std::size_t max_layout_edges = 5000;
  // Memory the caches may hold (least recently used entries go first).
  std::size_t data_cache_bytes = 128u << 20;     // per city version: projected network and POIs
  std::size_t layout_cache_bytes = 256u << 20;   // per parameter set: the answer and POI positions
  std::size_t tree_cache_bytes = 256u << 20;     // cluster trees (geographic and per layout)
  std::size_t worth_cache_bytes = 64u << 20;     // POI worth and cluster centres in lon/lat
};

class MetroService {
 public:
  // Without `mip`, MIPs are solved in this process (tests, benchmarks); the server passes a
  // child-process solver so that no request outlives its deadline.
  explicit MetroService(Catalog& catalog, MipSolver mip = {}, MetroLimits limits = {});

  Response layout(const Request& req, bool post);
  Response visual_worth(const Request& req);
  Response clusters(const Request& req);

  std::shared_ptr<const CityMetroData> data_for(const std::string& city_id);
  std::shared_ptr<const CityLayout> layout_for(const CityMetroData& data, const LayoutRequest& req, bool* cached);

 private:
  using LonLats = std::vector<geo::LonLat>;
  // A geographic cluster tree's node centres in lon/lat, and the tree they belong to (a tree
  // rebuilt under the same key, e.g. after a cache purge, gets its own).
  struct GeoCenters {
    std::weak_ptr<const poi::ClusterTree> tree;
    LonLats centers;
  };
  // A clusters query's tree and window in the tree's space; for the geographic tree also its
  // centres in lon/lat (null in layout space).
  struct ClusterWindow {
    std::shared_ptr<const poi::ClusterTree> tree;
    std::shared_ptr<const GeoCenters> centers;
    geo::XY lo, hi;
    bool empty = false;  // the window holds no POI: no clusters
  };
  // Writes cluster objects as JSON; `centers` null: the tree is in layout space.
  struct ClusterWriter {
    const poi::ClusterTree& tree;
    const std::vector<model::Poi>& pois;
    const LonLats* centers;

    // [{...}, ...] for `nodes`, with prominence[i] for nodes[i].
    void append_list(std::string& out, const std::vector<std::uint32_t>& nodes, const double* prominence) const;
    void append_cluster(std::string& out, std::uint32_t node, double prominence) const;
    void append_representative(std::string& out, std::uint32_t poi) const;
  };

  ClusterWindow geo_window(const CityMetroData& data, const std::string* bbox_text);
  ClusterWindow layout_window(const Request& req, const CityMetroData& data, const std::string* bbox_text);
  std::shared_ptr<const GeoCenters> geo_centers(const std::string& tree_key,
                                                const std::shared_ptr<const poi::ClusterTree>& tree,
                                                const geo::LocalProjection& projection);
  std::shared_ptr<const poi::ClusterTree> tree_for(const std::string& key, const std::vector<geo::XY>& points,
                                                   const std::vector<double>& worth, const std::vector<bool>* skip);

  Catalog& catalog_;
  MipSolver mip_;
  MetroLimits limits_;
  // Bounded in bytes (MetroLimits): a layout varies with its parameters, so a client can ask
  // for many; a cluster tree of 100,000 POIs holds 16 MB.
  LruCache<std::shared_ptr<const CityMetroData>> data_;
  LruCache<std::shared_ptr<const CityLayout>> layouts_;
  LruCache<std::shared_ptr<const poi::ClusterTree>> trees_;
  LruCache<std::shared_ptr<const std::vector<double>>> geo_worth_;
  LruCache<std::shared_ptr<const GeoCenters>> geo_centers_;  // by geographic tree key
  SingleFlight<std::shared_ptr<const CityLayout>> layout_flight_;
  SingleFlight<std::shared_ptr<const poi::ClusterTree>> tree_flight_;
};

}  // namespace tourmap::api
