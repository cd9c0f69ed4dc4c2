#pragma once
// The metro map endpoints (paper ch. 5): layouts, visual worth rasters and active POI clusters,
// with their caches: per city version the derived data and the geographic cluster tree; per
// (city version, parameters) the layout (also persisted in the store's result cache, since a
// large network takes seconds) and the layout-space cluster tree.
//
// Default layouts (solver=auto) are answered with the fast layout at once; the MIP polish runs
// afterwards in the background (LayoutImprover below) and, when it wins, replaces the cached
// layout and is announced through the event sink (WS /api/v1/events, wired by the server).

#include "catalog.hpp"
#include "cluster_tree_reuse.hpp"
#include "layout_improver.hpp"
#include "http.hpp"
#include "lru_cache.hpp"
#include "metro_layout.hpp"
#include "single_flight.hpp"

#include "poi/cluster_tree.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>

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
  // Background improvement of default layouts (solver=auto; see MetroService::layout):
  //   - one MIP at a time, on one dedicated thread at nice 10 (2 cores: foreground requests
  //     come first; the CBC child inherits the nice value);
  //   - at most `improve_queue` waiting, one per cache key; a new one at a full queue drops
  //     the oldest waiting one (counted; a later request for that layout schedules it again);
  //   - CBC gets `improve_mip_s` (serve --improve-mip): with the place term and the guards of
  //     metro/mip_polish.hpp it wins on Chicago (20 -> 15 bends, same displacement) after
  //     7-10 s and on Freiburg after 4-6 s; with 0.5 s (the old limit) it won nowhere;
  //   - its child is killed once it has used `improve_mip_grace_s` of CPU time past that
  //     (api::ChildClock::cpu; requests get 1 s of wall time): CBC overruns its limit in the
  //     root LP (1.2-1.5 s for 0.5 s when idle), and a nice-10 child on a busy machine gets
  //     little CPU, so wall-time kills lost every improvement under load; no client waits;
  //   - an improvement of a city version replaced meanwhile is dropped; shutdown stops the
  //     running one (its CBC child is killed) and drops the waiting ones.
  std::size_t improve_queue = 8;
  double improve_mip_s = 10.0;  // 0: no background improvements (default answers say "none")
  double improve_mip_grace_s = 3.0;
};

class MetroService {
 public:
  // Without `mip`, MIPs are solved in this process (tests, benchmarks); the server passes a
  // child-process solver so that no request outlives its deadline. `improve_mip` solves the
  // background improvements' MIPs (empty: `mip`).
  explicit MetroService(Catalog& catalog, MipSolver mip = {}, MetroLimits limits = {}, MipSolver improve_mip = {});
  ~MetroService();
  MetroService(const MetroService&) = delete;
  MetroService& operator=(const MetroService&) = delete;

  Response layout(const Request& req, bool post);
  Response visual_worth(const Request& req);
  Response clusters(const Request& req);

  std::shared_ptr<const CityMetroData> data_for(const std::string& city_id);
  std::shared_ptr<const CityLayout> layout_for(const CityMetroData& data, const LayoutRequest& req, bool* cached);

  // Gets a `layout_improved` event (JSON) whenever a background MIP replaced a cached default
  // layout; called on the improver's thread. A callback, so that api/ does not depend on the
  // server's WebSocket hub. Set it before serving.
  using EventSink = std::function<void(const std::string& json)>;
  void on_layout_improved(EventSink sink) { event_sink_ = std::move(sink); }
  struct ImprovementStats {
    LayoutImprover::Stats queue;
    std::uint64_t scheduled = 0, improved = 0, not_improved = 0, stale = 0;
  };
  ImprovementStats improvement_stats() const;
  // Cluster trees made since the start: built from scratch, or updated from the tree served
  // for the city's previous version (api/cluster_tree_reuse.hpp).
  std::uint64_t cluster_trees_built() const { return trees_built_; }
  std::uint64_t cluster_trees_updated() const { return trees_updated_; }
  // Shutdown: stop_improvements() waits for the improver's thread (a running MIP is killed);
  // call it before whatever the event sink publishes to goes away. request_stop_improvements()
  // only asks (for a signal handler that must not block).
  void request_stop_improvements() { improver_.request_stop(); }
  void stop_improvements() { improver_.stop(); }

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
    // With interests: the tree's leaves are the POIs of weight > 0, leaf_poi[leaf] the POI;
    // null: every POI, in order.
    std::shared_ptr<const std::vector<std::uint32_t>> leaf_poi;
  };
  // Writes cluster objects as JSON; `centers` null: the tree is in layout space.
  struct ClusterWriter {
    const poi::ClusterTree& tree;
    const std::vector<model::Poi>& pois;
    const LonLats* centers;
    const std::vector<std::uint32_t>* leaf_poi;  // see ClusterWindow

    // [{...}, ...] for `nodes`, with prominence[i] for nodes[i].
    void append_list(std::string& out, const std::vector<std::uint32_t>& nodes, const double* prominence) const;
    void append_cluster(std::string& out, std::uint32_t node, double prominence) const;
    void append_representative(std::string& out, std::uint32_t poi) const;
  };

  ClusterWindow geo_window(const Request& req, const CityMetroData& data, const std::string* bbox_text);
  ClusterWindow layout_window(const Request& req, const CityMetroData& data, const std::string* bbox_text);
  std::shared_ptr<const GeoCenters> geo_centers(const std::string& tree_key,
                                                const std::shared_ptr<const poi::ClusterTree>& tree,
                                                const geo::LocalProjection& projection);
  std::shared_ptr<const poi::ClusterTree> tree_for(const std::string& key, const std::vector<geo::XY>& points,
                                                   const std::vector<double>& worth, const std::vector<bool>* skip);
  std::shared_ptr<const CityLayout> compute_layout(const CityMetroData& data, const LayoutRequest& req);
  // The background improvement of a default layout (see MetroLimits and layout()).
  std::string automatic_answer(const std::shared_ptr<const CityMetroData>& data, const LayoutRequest& req,
                               const CityLayout& layout);
  void improve(const std::shared_ptr<const CityMetroData>& data, const LayoutRequest& req,
               const std::atomic<bool>& stop);
  void mark_not_improved(const std::string& key, const std::string& tried);
  void replace_layout(const std::string& key, const std::shared_ptr<const CityLayout>& layout);
  bool current_version(const CityMetroData& data);
  bool improvable(const CityMetroData& data) const;

  Catalog& catalog_;
  MipSolver mip_;
  MipSolver improve_mip_;
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
  LatestTrees latest_trees_;
  std::atomic<std::uint64_t> trees_built_{0}, trees_updated_{0};
  EventSink event_sink_;
  std::atomic<std::uint64_t> scheduled_{0}, improved_{0}, not_improved_{0}, stale_{0};
  // Last: destroyed first, so a running job never sees the caches above gone.
  LayoutImprover improver_;
};

}  // namespace tourmap::api
