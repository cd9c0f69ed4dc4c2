#include "metro/worth_approximation.hpp"

#include "util/stop.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace tourmap::metro::worth {
namespace {

constexpr double kLevelRatio = 1.1;             // H_{l+1} / H_l
constexpr std::size_t kLevelsPerGrid = 7;       // levels sharing one grid (1.1^7 = 1.95)
constexpr int kCellsPerH = 3;                   // grid cell = (the grid's narrowest H) / 3
constexpr int kTile = 64;                       // nodes a tile owns per side
constexpr int kStore = kTile + 3;               // nodes a tile stores per side: -1 .. kTile + 1
constexpr int kMaxRadius = 4 * kCellsPerH * 2;  // taps each side for the widest level of a grid
constexpr int kMaxWindow = kStore + 2 * kMaxRadius;
constexpr std::size_t kMaxTiles = std::size_t{1} << 20;        // per grid's tile index
constexpr std::size_t kMaxBucketCells = std::size_t{1} << 20;  // per exact band's bucket grid
static_assert(kMaxRadius + 3 <= kTile, "a tile's window must reach only its 8 neighbours");

// The planner's cost model, in multiply-adds of the grids' convolutions (vectorised floats,
// ~0.1 ns each here). A tile of one level on its own grid (cell H / 3, 25 taps per pass) costs
// kTileCost; on a shared grid a level costs ~2.2 times that (finer cells, more taps for the
// wider levels). A kernel in reach summed from an exact band costs kExactCost (~15 ns: the
// scan checks ~2.3 kernels per kernel in reach, and an exp). Measured on 250K and 1M POIs, the
// total time changes by less than 20 % for kExactCost between 40 and 1000: a broad optimum.
constexpr double kExactCost = 150.0;
constexpr double kTileCost = 2.2 * (double(kStore + 24) * kStore * 25 + double(kStore) * kStore * 25);
constexpr double kSplatCost = 60.0;                   // per contribution: weights, splat, sorting
constexpr double kPointCost = 40.0 / kLevelsPerGrid;  // per point and level: its share of an interpolation

// Catmull-Rom weights of nodes -1, 0, 1, 2 at fraction t in [0, 1): interpolation reproduces
// quadratics (error O(cell^3)); splatting with the same weights is its transpose.
inline void cubic_weights(double t, double w[4]) {
  const double t2 = t * t, t3 = t2 * t;
  w[0] = 0.5 * (-t3 + 2 * t2 - t);
  w[1] = 0.5 * (3 * t3 - 5 * t2 + 2);
  w[2] = 0.5 * (-3 * t3 + 4 * t2 + t);
  w[3] = 0.5 * (t3 - t2);
}

// POIs summed exactly in the approximation (the narrow ones), in a bucket grid per band of
// bandwidths (factor sqrt 2): a point scans, row by row, the contiguous buckets within the
// band's reach.
class ExactBand {
 public:
  ExactBand(const std::vector<XY>& pos, const std::vector<double>& bandwidth, const std::vector<double>& weight,
            const std::vector<std::uint32_t>& members) {
    Bounds box;
    double hmax = 0;
    for (auto i : members) {
      box.add(pos[i]);
      hmax = std::max(hmax, bandwidth[i]);
    }
    reach_ = 4 * hmax;
    const double w = box.hi.x - box.lo.x, h = box.hi.y - box.lo.y;
    cell_ = std::max({hmax, std::sqrt(w * h / kMaxBucketCells), std::max(w, h) / 4096, 1e-9});
    origin_ = box.lo;
    nx_ = static_cast<int>(w / cell_) + 1;
    ny_ = static_cast<int>(h / cell_) + 1;
    std::vector<std::uint32_t> cell_of(members.size());
    start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
    for (std::size_t k = 0; k < members.size(); ++k) {
      const auto& p = pos[members[k]];
      int i = std::min(static_cast<int>((p.x - origin_.x) / cell_), nx_ - 1);
      int j = std::min(static_cast<int>((p.y - origin_.y) / cell_), ny_ - 1);
      cell_of[k] = static_cast<std::uint32_t>(j) * nx_ + i;
      ++start_[cell_of[k] + 1];
    }
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    kernels_.resize(members.size());
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t k = 0; k < members.size(); ++k) {
      const auto i = members[k];
      const double hh = bandwidth[i] * bandwidth[i];
      const double coef = 1.0 / (2 * M_PI * hh * hh);
      kernels_[fill[cell_of[k]]++] = {pos[i].x, pos[i].y, -1.0 / (2 * hh), 16 * hh, weight.empty() ? coef : weight[i] * coef};
    }
  }

  double sum(XY q) const {
    const double fx0 = std::floor((q.x - reach_ - origin_.x) / cell_), fx1 = std::floor((q.x + reach_ - origin_.x) / cell_);
    const double fy0 = std::floor((q.y - reach_ - origin_.y) / cell_), fy1 = std::floor((q.y + reach_ - origin_.y) / cell_);
    if (!(fx1 >= 0 && fy1 >= 0 && fx0 < nx_ && fy0 < ny_)) return 0.0;
    const int i0 = static_cast<int>(std::max(0.0, fx0)), i1 = static_cast<int>(std::min(nx_ - 1.0, fx1));
    const int j0 = static_cast<int>(std::max(0.0, fy0)), j1 = static_cast<int>(std::min(ny_ - 1.0, fy1));
    double s = 0;
    for (int j = j0; j <= j1; ++j) {
      const std::uint32_t* row = &start_[static_cast<std::size_t>(j) * nx_];
      for (std::uint32_t k = row[i0], end = row[i1 + 1]; k < end; ++k) {
        const Kernel& K = kernels_[k];
        const double dx = q.x - K.x, dy = q.y - K.y, d2 = dx * dx + dy * dy;
        if (d2 <= K.r2) s += K.coef * std::exp(K.a * d2);
      }
    }
    return s;
  }

 private:
  struct Kernel {
    double x, y;
    double a;     // -1 / (2 h^2)
    double r2;    // (4 h)^2
    double coef;  // 1 / (2 pi h^4), times the POI's weight
  };
  XY origin_;
  double cell_ = 1, reach_ = 0;
  int nx_ = 1, ny_ = 1;
  std::vector<std::uint32_t> start_;
  std::vector<Kernel> kernels_;
};

// A tiled grid: nodes at origin + (kx, ky) * cell; tile (tx, ty) owns nodes
// [tx * kTile, tx * kTile + kTile) per axis and stores the field on its nodes -1 .. kTile + 1,
// enough to interpolate any point whose node it owns. Tiles exist only where asked for.
struct TiledGrid {
  double cell = 0;
  XY origin;
  int nx = 0, ny = 0;  // tiles per axis
  std::vector<std::int32_t> tile;  // tile id or -1
  std::vector<float> data;         // kStore^2 per tile

  // Covers `all` with room for kernels of up to `radius` nodes; false when the tile index
  // would be too large.
  bool place(const Bounds& all, double cell_m, int radius) {
    cell = cell_m;
    const double margin = (kTile + radius + 8) * cell;
    origin = {all.lo.x - margin, all.lo.y - margin};
    const double nxf = std::floor(((all.hi.x - origin.x) / cell + radius + 8) / kTile) + 1;
    const double nyf = std::floor(((all.hi.y - origin.y) / cell + radius + 8) / kTile) + 1;
    if (!(nxf * nyf <= double(kMaxTiles))) return false;
    nx = static_cast<int>(nxf);
    ny = static_cast<int>(nyf);
    return true;
  }
  int node(double v, double o) const { return static_cast<int>(std::floor((v - o) / cell)); }
  std::size_t tiles() const { return static_cast<std::size_t>(nx) * ny; }

  // Marks the tiles holding a point of `density` (conservatively: whole cells).
  void mark_points(const PointDensity& density, std::vector<std::uint8_t>& marks) const {
    marks.assign(tiles(), 0);
    const double tile_m = kTile * cell;
    auto tile_index = [&](double v, double o, int n) {  // clamped to the grid: -1 or n outside
      return static_cast<int>(std::clamp(std::floor((v - o) / tile_m), -1.0, double(n)));
    };
    density.for_each_occupied(tile_m, [&](XY lo, XY hi) {
      const int tx0 = std::max(0, tile_index(lo.x, origin.x, nx)), tx1 = std::min(nx - 1, tile_index(hi.x, origin.x, nx));
      const int ty0 = std::max(0, tile_index(lo.y, origin.y, ny)), ty1 = std::min(ny - 1, tile_index(hi.y, origin.y, ny));
      for (int ty = ty0; ty <= ty1; ++ty)
        for (int tx = tx0; tx <= tx1; ++tx) marks[static_cast<std::size_t>(ty) * nx + tx] = 1;
    });
  }
  std::size_t tile_of(XY p) const {
    return static_cast<std::size_t>(node(p.y, origin.y) / kTile) * nx + static_cast<std::size_t>(node(p.x, origin.x) / kTile);
  }
  // `marks` and their 8 neighbours: the tiles a kernel whose node lies in a marked tile can
  // reach (its splat and cut reach fewer than kTile nodes).
  std::vector<std::uint8_t> dilate(const std::vector<std::uint8_t>& marks) const {
    std::vector<std::uint8_t> out(marks.size(), 0);
    for (int ty = 0; ty < ny; ++ty)
      for (int tx = 0; tx < nx; ++tx)
        if (marks[static_cast<std::size_t>(ty) * nx + tx])
          for (int y = std::max(0, ty - 1); y <= std::min(ny - 1, ty + 1); ++y)
            for (int x = std::max(0, tx - 1); x <= std::min(nx - 1, tx + 1); ++x) out[static_cast<std::size_t>(y) * nx + x] = 1;
    return out;
  }

  double interpolate(XY q) const {
    const double fx = (q.x - origin.x) / cell, fy = (q.y - origin.y) / cell;
    const double kxf = std::floor(fx), kyf = std::floor(fy);
    if (!(kxf >= 0 && kyf >= 0 && kxf < double(nx) * kTile && kyf < double(ny) * kTile)) return 0.0;
    const int kx = static_cast<int>(kxf), ky = static_cast<int>(kyf);
    const int tx = kx / kTile, ty = ky / kTile;
    const std::int32_t id = tile[static_cast<std::size_t>(ty) * nx + tx];
    if (id < 0) return 0.0;
    double wx[4], wy[4];
    cubic_weights(fx - kxf, wx);
    cubic_weights(fy - kyf, wy);
    // Node kx - 1 is stored at column kx - tx * kTile.
    const float* d = &data[static_cast<std::size_t>(id) * kStore * kStore +
                           static_cast<std::size_t>(ky - ty * kTile) * kStore + (kx - tx * kTile)];
    double s = 0;
    for (int b = 0; b < 4; ++b, d += kStore) s += wy[b] * (wx[0] * d[0] + wx[1] * d[1] + wx[2] * d[2] + wx[3] * d[3]);
    return s;
  }
};

// A POI's place among the levels: between H_b and H_{b+1}, with the shares of its mass that
// keep the kernel's mass (1/h^2) and second moment (h^2): linear in h^2.
struct Bracket {
  std::uint32_t b = 0;
  double lower = 1, upper = 0;
};

class Approximation {
 public:
  Approximation(const std::vector<XY>& pos, const std::vector<double>& bandwidth, const std::vector<double>& weight,
                std::size_t point_count, const PointDensity& density, const std::vector<double>& exact_work,
                bool grids_only)
      : pos_(pos), bandwidth_(bandwidth), weight_(weight) {
    const std::size_t n = pos.size();
    double hmin = std::numeric_limits<double>::infinity(), hmax = 0;
    for (double h : bandwidth) {
      hmin = std::min(hmin, h);
      hmax = std::max(hmax, h);
    }
    const double log_ratio = std::log(kLevelRatio);
    std::size_t levels = 1;
    if (hmax > hmin * (1 + 1e-12)) levels = static_cast<std::size_t>(std::floor(std::log(hmax / hmin) / log_ratio)) + 2;
    const std::size_t brackets = std::max<std::size_t>(1, levels - 1);
    H_.resize(levels);
    for (std::size_t l = 0; l < levels; ++l) H_[l] = hmin * std::pow(kLevelRatio, static_cast<double>(l));

    bracket_.resize(n);
    std::vector<double> exact_per_bracket(brackets, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      Bracket& br = bracket_[i];
      const double h = bandwidth[i];
      if (levels > 1) {
        br.b = static_cast<std::uint32_t>(std::clamp(std::floor(std::log(h / hmin) / log_ratio), 0.0, double(levels - 2)));
        const double a2 = H_[br.b] * H_[br.b], b2 = H_[br.b + 1] * H_[br.b + 1];
        br.upper = std::clamp((h * h - a2) / (b2 - a2), 0.0, 1.0);
        br.lower = 1 - br.upper;
      }
      exact_per_bracket[br.b] += exact_work[i];
    }

    // The grid cost per level, as if on its own grid (cell H / 3): its tiles near both points
    // and its POIs.
    for (const auto& p : pos) poi_bounds_.add(p);
    point_bounds_ = density.bounds();
    std::vector<TiledGrid> own(levels);
    std::vector<std::vector<std::uint8_t>> near_points(levels), near_sources(levels);
    std::vector<std::size_t> contributions(levels, 0);
    for (std::size_t l = 0; l < levels; ++l) {
      util::check_stop();
      if (!own[l].place(grid_bounds(4 * H_[l]), H_[l] / kCellsPerH, 4 * kCellsPerH)) continue;
      own[l].mark_points(density, near_points[l]);
      near_sources[l].assign(own[l].tiles(), 0);
    }
    // A kernel reaches at most the 3 x 3 tiles around its own: mark its tile, count the tiles
    // next to a marked one (a little high for isolated POIs).
    for (std::size_t i = 0; i < n; ++i) {
      if (i % (16 * kStopEvery) == 0) util::check_stop();
      const Bracket& br = bracket_[i];
      for (std::size_t l = br.b; l <= std::min<std::size_t>(br.b + 1, levels - 1); ++l) {
        const TiledGrid& g = own[l];
        if (g.nx == 0) continue;
        ++contributions[l];
        near_sources[l][g.tile_of(pos[i])] = 1;
      }
    }
    std::vector<double> grid_cost(levels, std::numeric_limits<double>::infinity());
    for (std::size_t l = 0; l < levels; ++l) {
      const TiledGrid& g = own[l];
      if (g.nx == 0) continue;
      const auto reach = g.dilate(near_sources[l]);
      std::size_t active = 0;
      for (std::size_t t = 0; t < reach.size(); ++t) active += reach[t] && near_points[l][t];
      grid_cost[l] = active * kTileCost + contributions[l] * kSplatCost + point_count * kPointCost;
    }

    // Threshold t: POIs in brackets below t are summed exactly, the others go on the grids of
    // levels >= t. The cheapest.
    std::vector<double> grid_from(levels + 1, 0.0);  // cost of levels >= l
    for (std::size_t l = levels; l-- > 0;) grid_from[l] = grid_from[l + 1] + grid_cost[l];
    double best = std::numeric_limits<double>::infinity(), exact_below = 0;
    for (std::size_t t = 0; t <= (grids_only ? 0 : brackets); ++t) {
      const double cost = exact_below * kExactCost + (t < brackets ? grid_from[t] : 0.0);
      if (cost < best) {
        best = cost;
        threshold_ = t;
      }
      if (t < brackets) exact_below += exact_per_bracket[t];
    }
    // The grids: levels t .. t + 6 on one, and so on. A grid too large for its tile index
    // (POIs and points spread over thousands of km) moves its levels to the exact bands.
    std::vector<TiledGrid> grids;
    for (bool placed = false; !placed;) {
      placed = true;
      grids.clear();
      for (std::size_t l = threshold_ < brackets ? threshold_ : levels; l < levels && placed; l += kLevelsPerGrid) {
        const std::size_t l1 = std::min(levels, l + kLevelsPerGrid);
        grids.emplace_back();
        if (!grids.back().place(grid_bounds(4 * H_[l1 - 1]), H_[l] / kCellsPerH, kMaxRadius)) {
          threshold_ = std::min(l1, brackets);
          placed = false;
        }
      }
    }
    build_exact();
    for (std::size_t k = 0; k < grids.size(); ++k) {
      const std::size_t l0 = threshold_ + k * kLevelsPerGrid;
      build_grid(density, std::move(grids[k]), l0, std::min(levels, l0 + kLevelsPerGrid));
    }
  }

  // Adds the kernel sums at the points to `out`: band by band, grid by grid (one grid's tiles
  // at a time stay in cache).
  void sum(std::span<const XY> points, std::vector<double>& out) const {
    for (const auto& band : bands_)
      for (std::size_t k = 0; k < points.size(); ++k) {
        if (k % kStopEvery == 0) util::check_stop();
        out[k] += band.sum(points[k]);
      }
    for (const auto& g : grids_)
      for (std::size_t k = 0; k < points.size(); ++k) {
        if (k % (4 * kStopEvery) == 0) util::check_stop();
        out[k] += g.interpolate(points[k]);
      }
  }

  std::size_t exact_sources() const { return exact_sources_; }
  std::size_t grid_levels() const { return grid_levels_; }
  std::size_t tiles() const { return tiles_; }

 private:
  bool exact(std::size_t i) const { return bracket_[i].b < threshold_; }

  // What a grid for kernels reaching `reach` metres covers: the POIs, and the points within
  // their reach (points elsewhere get nothing from it).
  Bounds grid_bounds(double reach) const {
    Bounds b = poi_bounds_;
    const XY lo{std::max(point_bounds_.lo.x, poi_bounds_.lo.x - reach), std::max(point_bounds_.lo.y, poi_bounds_.lo.y - reach)};
    const XY hi{std::min(point_bounds_.hi.x, poi_bounds_.hi.x + reach), std::min(point_bounds_.hi.y, poi_bounds_.hi.y + reach)};
    if (lo.x <= hi.x && lo.y <= hi.y) {
      b.add(lo);
      b.add(hi);
    }
    return b;
  }

  void build_exact() {
    // Bands of bandwidth by factor sqrt(2) from the narrowest.
    const double hmin = H_.front();
    std::vector<std::vector<std::uint32_t>> bands;
    for (std::uint32_t i = 0; i < pos_.size(); ++i) {
      if (!exact(i)) continue;
      const auto band = static_cast<std::size_t>(std::max(0.0, std::floor(2 * std::log2(bandwidth_[i] / hmin))));
      if (band >= bands.size()) bands.resize(band + 1);
      bands[band].push_back(i);
      ++exact_sources_;
    }
    for (const auto& members : bands) {
      util::check_stop();
      if (!members.empty()) bands_.emplace_back(pos_, bandwidth_, weight_, members);
    }
  }

  // Levels [l0, l1) on one grid with cell H_l0 / 3: every level's contributions splatted onto
  // the grid, convolved with that level's Gaussian (separable, cut at 4 H_l) and summed.
  void build_grid(const PointDensity& density, TiledGrid g, std::size_t l0, std::size_t l1) {
    util::check_stop();
    const std::size_t count = l1 - l0;
    const double cell = g.cell;
    std::vector<int> radius(count);
    std::vector<std::vector<float>> gauss(count);
    for (std::size_t j = 0; j < count; ++j) {
      const double H = H_[l0 + j];
      radius[j] = std::min(kMaxRadius, static_cast<int>(std::floor(4 * H / cell + 1e-9)));
      for (int k = -radius[j]; k <= radius[j]; ++k)
        gauss[j].push_back(static_cast<float>(std::exp(-(k * cell) * (k * cell) / (2 * H * H))));
    }

    // Contributions, by level and tile: the POI's node and its mass in units of the level's
    // exp(-d^2 / 2 H^2). A POI's kernel is 1/h^2 times a unit-mass Gaussian of bandwidth h;
    // a unit-mass Gaussian of bandwidth H peaks at 1/(2 pi H^2).
    struct Contribution {
      std::int32_t kx, ky;
      float fx, fy;  // fractions within the node's cell
      float mass;
    };
    std::vector<std::uint8_t> near_points, own_tile(g.tiles(), 0);
    g.mark_points(density, near_points);
    const std::size_t tiles = g.tiles();
    std::vector<std::uint32_t> start(count * tiles + 1, 0);  // bucket j * tiles + t
    std::vector<std::uint32_t> key;
    std::vector<Contribution> contrib;
    for (std::uint32_t i = 0; i < pos_.size(); ++i) {  // in memory order: faster than by bracket
      if (i % (16 * kStopEvery) == 0) util::check_stop();
      const Bracket& br = bracket_[i];
      if (br.b + 1 < l0 || br.b >= l1 || br.b < threshold_) continue;
      const double fx = (pos_[i].x - g.origin.x) / g.cell, fy = (pos_[i].y - g.origin.y) / g.cell;
      const double kxf = std::floor(fx), kyf = std::floor(fy);
      const int kx = static_cast<int>(kxf), ky = static_cast<int>(kyf);
      const std::size_t t = static_cast<std::size_t>(ky / kTile) * g.nx + static_cast<std::size_t>(kx / kTile);
      for (std::size_t l = std::max<std::size_t>(br.b, l0); l <= br.b + 1u && l < l1; ++l) {
        const double share = H_.size() == 1 ? 1.0 : l == br.b ? br.lower : br.upper;
        if (share <= 0) continue;
        const double h = bandwidth_[i], H = H_[l];
        const double mass = share / (h * h) / (2 * M_PI * H * H);
        key.push_back(static_cast<std::uint32_t>((l - l0) * tiles + t));
        contrib.push_back({kx, ky, static_cast<float>(fx - kxf), static_cast<float>(fy - kyf),
                           static_cast<float>(weight_.empty() ? mass : weight_[i] * mass)});
        ++start[key.back() + 1];
        own_tile[t] = 1;
      }
    }
    for (std::size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
    std::vector<Contribution> sorted(contrib.size());
    {
      std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
      for (std::size_t k = 0; k < contrib.size(); ++k) sorted[fill[key[k]]++] = contrib[k];
    }
    contrib = {};
    key = {};

    // The tiles near both points and contributions get a slot.
    const auto near_sources = g.dilate(own_tile);
    std::vector<std::size_t> active;
    g.tile.assign(tiles, -1);
    for (std::size_t t = 0; t < tiles; ++t)
      if (near_points[t] && near_sources[t]) {
        g.tile[t] = static_cast<std::int32_t>(active.size());
        active.push_back(t);
      }
    g.data.assign(active.size() * kStore * kStore, 0.0f);
    std::vector<std::uint8_t> used(active.size(), 0);

    constexpr std::size_t kArea = static_cast<std::size_t>(kStore) * kStore;
    std::vector<std::int32_t> splat_slot(tiles, -1);
    std::vector<float> splat;  // per tile with contributions: its nodes tx * kTile - 1 .. + kTile + 1
    struct Box {
      int x0, x1, y0, y1;  // splat bounds in the tile's stored nodes
    };
    std::vector<Box> splat_box;
    std::vector<float> window(static_cast<std::size_t>(kMaxWindow) * kMaxWindow, 0.0f);
    std::vector<float> pass(static_cast<std::size_t>(kMaxWindow) * kStore);
    for (std::size_t j = 0; j < count; ++j) {
      util::check_stop();
      // 1. Splat the level's contributions, each once, into its tile's array.
      std::fill(splat_slot.begin(), splat_slot.end(), -1);
      splat.clear();
      splat_box.clear();
      for (std::size_t t = 0; t < tiles; ++t) {
        const std::uint32_t b = start[j * tiles + t], e = start[j * tiles + t + 1];
        if (b == e) continue;
        splat_slot[t] = static_cast<std::int32_t>(splat_box.size());
        splat.resize(splat.size() + kArea, 0.0f);
        float* dst = &splat[splat.size() - kArea];
        const int tx0 = static_cast<int>(t % g.nx) * kTile, ty0 = static_cast<int>(t / g.nx) * kTile;
        Box box{kStore, -1, kStore, -1};
        for (std::uint32_t k = b; k < e; ++k) {
          const Contribution& c = sorted[k];
          double wx[4], wy[4];
          cubic_weights(c.fx, wx);
          cubic_weights(c.fy, wy);
          const int x = c.kx - tx0, y = c.ky - ty0;  // node kx - 1 is stored at x
          for (int v = 0; v < 4; ++v) {
            float* row = dst + static_cast<std::size_t>(y + v) * kStore + x;
            const double m = c.mass * wy[v];
            for (int u = 0; u < 4; ++u) row[u] += static_cast<float>(m * wx[u]);
          }
          box = {std::min(box.x0, x), std::max(box.x1, x + 3), std::min(box.y0, y), std::max(box.y1, y + 3)};
        }
        splat_box.push_back(box);
      }
      // 2. Per active tile: gather the splats within reach into a window, convolve, add.
      const int r = radius[j], w = kStore + 2 * r;
      const float* gk = gauss[j].data();
      for (std::size_t a = 0; a < active.size(); ++a) {
        if (a % 16 == 0) util::check_stop();
        const int tx = static_cast<int>(active[a] % g.nx), ty = static_cast<int>(active[a] / g.nx);
        // Window column x is node tx * kTile - 1 - r + x; a tile's stored column u is node
        // tx' * kTile - 1 + u: x = u + (tx' - tx) * kTile + r.
        int bx0 = w, bx1 = -1, by0 = w, by1 = -1;
        for (int ny = std::max(0, ty - 1); ny <= std::min(g.ny - 1, ty + 1); ++ny)
          for (int nx = std::max(0, tx - 1); nx <= std::min(g.nx - 1, tx + 1); ++nx) {
            const std::int32_t slot = splat_slot[static_cast<std::size_t>(ny) * g.nx + nx];
            if (slot < 0) continue;
            const Box& sb = splat_box[slot];
            const int dx = (nx - tx) * kTile + r, dy = (ny - ty) * kTile + r;
            const int x0 = std::max(sb.x0 + dx, 0), x1 = std::min(sb.x1 + dx, w - 1);
            const int y0 = std::max(sb.y0 + dy, 0), y1 = std::min(sb.y1 + dy, w - 1);
            if (x0 > x1 || y0 > y1) continue;
            const float* src = &splat[static_cast<std::size_t>(slot) * kArea];
            for (int y = y0; y <= y1; ++y) {
              float* dst = &window[static_cast<std::size_t>(y) * w];
              const float* s = src + static_cast<std::size_t>(y - dy) * kStore - dx;
              for (int x = x0; x <= x1; ++x) dst[x] += s[x];
            }
            bx0 = std::min(bx0, x0);
            bx1 = std::max(bx1, x1);
            by0 = std::min(by0, y0);
            by1 = std::max(by1, y1);
          }
        if (bx1 < bx0) continue;
        used[a] = 1;
        // Separable convolution, only where the splat reaches: along x into `pass` (the
        // splat's rows, the stored columns), then along y into the tile.
        const int cx0 = std::max(0, bx0 - 2 * r), cx1 = std::min(kStore - 1, bx1);
        for (int y = by0; y <= by1; ++y) {
          float* dst = &pass[static_cast<std::size_t>(y) * kStore];
          std::fill(dst + cx0, dst + cx1 + 1, 0.0f);
          float* src = &window[static_cast<std::size_t>(y) * w];
          for (int k = 0; k <= 2 * r; ++k) {
            const float gv = gk[k];
            const float* s = src + k;
            for (int x = cx0; x <= cx1; ++x) dst[x] += gv * s[x];
          }
          std::fill(src + bx0, src + bx1 + 1, 0.0f);  // clean for the next window
        }
        float* out = &g.data[a * kArea];
        const int oy0 = std::max(0, by0 - 2 * r), oy1 = std::min(kStore - 1, by1);
        for (int y = oy0; y <= oy1; ++y) {
          float* dst = out + static_cast<std::size_t>(y) * kStore;
          for (int k = std::max(0, by0 - y); k <= std::min(2 * r, by1 - y); ++k) {
            const float gv = gk[k];
            const float* s = &pass[static_cast<std::size_t>(y + k) * kStore];
            for (int x = cx0; x <= cx1; ++x) dst[x] += gv * s[x];
          }
        }
      }
    }
    // Drop the tiles nothing reached.
    std::size_t kept = 0;
    for (std::size_t a = 0; a < active.size(); ++a) {
      if (!used[a]) {
        g.tile[active[a]] = -1;
        continue;
      }
      if (kept != a) std::copy_n(&g.data[a * kArea], kArea, &g.data[kept * kArea]);
      g.tile[active[a]] = static_cast<std::int32_t>(kept++);
    }
    g.data.resize(kept * kArea);
    tiles_ += kept;
    grid_levels_ += count;
    grids_.push_back(std::move(g));
  }

  const std::vector<XY>& pos_;
  const std::vector<double>& bandwidth_;
  const std::vector<double>& weight_;  // empty: 1
  Bounds poi_bounds_, point_bounds_;
  std::vector<double> H_;
  std::vector<Bracket> bracket_;
  std::vector<ExactBand> bands_;
  std::vector<TiledGrid> grids_;
  std::size_t threshold_ = 0;
  std::size_t exact_sources_ = 0;
  std::size_t grid_levels_ = 0;
  std::size_t tiles_ = 0;
};

}  // namespace

ApproximationReport approximate_worth(const std::vector<XY>& pos, const std::vector<double>& bandwidth,
                                      const std::vector<double>& weight, std::span<const XY> points,
                                      const PointDensity& density, const std::vector<double>& exact_work,
                                      bool grids_only, std::vector<double>& out) {
  Approximation approx(pos, bandwidth, weight, points.size(), density, exact_work, grids_only);
  approx.sum(points, out);
  return {approx.exact_sources(), approx.grid_levels(), approx.tiles()};
}

}  // namespace tourmap::metro::worth
