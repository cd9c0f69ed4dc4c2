// Crowd rendering benchmark (paper 3.6, Table 3.1) on the real code path: the service's
// CrowdAssets (glTF load, Loop subdivision, VDR-AM hierarchy), the scene placement and frame
// request the stream uses, the EGL/OpenGL renderer (Mesa llvmpipe here) and the JPEG encoder.
//   1. construction per character: triangles, time, leaf clusters, representative poses,
//      bytes per triangle;
//   2. error-aware vs octree leaf clusters: triangles in the VDR cut of the office scene at the
//      same PoE (paper: ~50% fewer with error-aware);
//   3. LOD cut time for 1K characters (paper: < 1.5 ms) and JPEG encode time per frame;
//   4. Table 3.1: fps and rendered triangles for NoLOD, VDR, VDR+OC at 1280x720, PoE 0.5 and a
//      streaming PoE, and the speedup of VDR+OC over NoLOD measured in the same run.
//
//   build/bench/crowd_bench [--scenes office,exhibition,stampede] [--frames 8] [--nolod-frames 2]
//       [--width 1280] [--height 720] [--stream-poe 2] [--db FILE] [--max-subdivision -1]
//       [--data-dir DIR]
// --db keeps built hierarchies between runs (the first run builds them).

#include "api/crowd_assets.hpp"
#include "crowd/hierarchy_build.hpp"
#include "crowd/hierarchy_io.hpp"
#include "crowd/cut_instances.hpp"
#include "crowd/lod_cut.hpp"
#include "render/camera.hpp"
#include "render/crowd_renderer.hpp"
#include "render/egl_context.hpp"
#include "render/jpeg_encoder.hpp"
#include "server/crowd_scene_render.hpp"
#include "store/migrate.hpp"
#include "util/fork_join.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

using namespace tourmap;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

struct Options {
  std::vector<std::string> scenes = {"office", "exhibition", "stampede"};
  int frames = 8, nolod_frames = 2, width = 1280, height = 720, max_subdivision = -1;
  float stream_poe = 2;
  std::string db, data_dir = TOURMAP_DEFAULT_DATA_DIR;
};

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string part; std::getline(in, part, ',');)
    if (!part.empty()) out.push_back(part);
  return out;
}

// Frame k of the benchmark's camera path: the default camera orbiting its target by 1.5 degrees
// per frame (coherent motion, as a user dragging the view), the animation advancing 1/30 s.
server::SceneCamera path_camera(const crowd::SceneState& s, int k, int width, int height) {
  const auto& c = s.default_camera;
  const float a = static_cast<float>(k) * 1.5f * 3.14159265f / 180.f;
  const crowd::Vec3 d = c.eye - c.target;
  const crowd::Vec3 rotated(std::cos(a) * d.x() - std::sin(a) * d.z(), d.y(), std::sin(a) * d.x() + std::cos(a) * d.z());
  return {c.target + rotated, c.target, c.fov_deg, width, height};
}

struct ModeResult {
  double fps = 0, triangles = 0, lod_cut_ms = 0, render_ms = 0, occluded = 0, frustum_culled = 0, queries = 0;
  int frames = 0;
};

ModeResult run_mode(render::CrowdRenderer& renderer, const server::PreparedScene& p, render::RenderMode mode, float poe,
                    int frames, const Options& o) {
  ModeResult r;
  renderer.reset_coherence();
  std::vector<std::uint8_t> rgba;
  std::vector<crowd::Placement> scratch;
  render::FrameRequest req;
  double total_ms = 0;
  // One untimed frame first: the PVS of VDR+OC starts from the previous frame, as in a stream.
  for (int k = -1; k < frames; ++k) {
    const int step = std::max(k, 0);
    server::scene_frame_request(p, step / 30.0, path_camera(p.scene, step, o.width, o.height), mode, poe, false, req,
                                scratch);
    render::FrameStats fs{};
    const auto t0 = Clock::now();
    renderer.render(req, rgba, fs);
    const double ms = ms_since(t0);
    if (k < 0) continue;
    total_ms += ms;
    r.triangles += static_cast<double>(fs.triangles);
    r.lod_cut_ms += fs.lod_cut_ms;
    r.render_ms += fs.render_ms + fs.readback_ms;
    r.occluded += static_cast<double>(fs.occluded);
    r.frustum_culled += static_cast<double>(fs.frustum_culled);
    r.queries += static_cast<double>(fs.occlusion_queries);
    ++r.frames;
  }
  const double n = std::max(1, r.frames);
  r.fps = total_ms > 0 ? 1000.0 * r.frames / total_ms : 0;
  r.triangles /= n;
  r.lod_cut_ms /= n;
  r.render_ms /= n;
  r.occluded /= n;
  r.frustum_culled /= n;
  r.queries /= n;
  return r;
}

// Section 3's same-run baseline: the LOD cut walk as it was before issue 18 (recursive over
// ClusterHierarchy, each cluster's box moved to a world-space AABB, 6 planes and tan(fov/2) per
// visited cluster). Its rule differs slightly from the new lod_cut: it tests the world AABB of
// the transformed box, not the oriented box, so it culls less and draws a little more.
namespace baseline {

struct WorldBox {
  crowd::Vec3 center, extent;
};

WorldBox to_world(const crowd::Box3& box, const crowd::Affine& world) {
  const crowd::Vec3 c = box.center();
  const crowd::Vec3 e = box.sizes() * 0.5f;
  return {world * c, world.linear().cwiseAbs() * e};
}

bool outside_frustum(const WorldBox& b, const std::array<Eigen::Vector4f, 6>& planes) {
  for (const auto& p : planes) {
    const float reach = std::abs(p.x()) * b.extent.x() + std::abs(p.y()) * b.extent.y() +
                        std::abs(p.z()) * b.extent.z();
    if (p.head<3>().dot(b.center) + p.w() + reach < 0) return true;
  }
  return false;
}

struct CutWalk {
  const crowd::ClusterHierarchy& h;
  const crowd::Affine& world;
  const crowd::CameraView& view;
  float poe;
  float scale;
  std::array<Eigen::Vector4f, 6> planes;
  std::vector<int>& out;
  crowd::CutStats& stats;

  void visit(int id) {
    const crowd::Cluster& c = h.clusters[static_cast<std::size_t>(id)];
    ++stats.visited;
    const WorldBox box = to_world(c.bounds, world);
    if (outside_frustum(box, planes)) {
      ++stats.frustum_culled;
      return;
    }
    const float dist = ((view.eye - box.center).cwiseAbs() - box.extent).cwiseMax(0.f).norm();
    const bool fine_enough = c.is_leaf() || (poe > 0 && crowd::projected_diameter_px(c.error * scale, dist, view) <= poe);
    if (fine_enough) {
      out.push_back(id);
      ++stats.drawn;
      stats.triangles += c.triangle_count();
      return;
    }
    visit(c.children[0]);
    visit(c.children[1]);
  }
};

void lod_cut(const crowd::ClusterHierarchy& h, const crowd::Affine& world, const crowd::CameraView& view, float poe,
             std::vector<int>& out, crowd::CutStats& stats) {
  if (h.root < 0) return;
  const Eigen::Matrix4f& m = view.view_proj;
  const Eigen::Vector4f r0 = m.row(0), r1 = m.row(1), r2 = m.row(2), r3 = m.row(3);
  CutWalk walk{h, world, view, poe, world.linear().col(0).norm(), {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r3 + r2, r3 - r2},
               out, stats};
  walk.visit(h.root);
}

}  // namespace baseline

// Triangles in the VDR cut (frustum-culled, no occlusion) of a scene's characters, with one
// hierarchy per character, at the default camera.
double cut_triangles(const server::PreparedScene& p, const std::vector<const crowd::ClusterHierarchy*>& hierarchies,
                     const Options& o, float poe) {
  const auto cam = path_camera(p.scene, 0, o.width, o.height);
  const crowd::CameraView view = render::make_camera_view(cam.eye, cam.target, crowd::Vec3::UnitY(),
                                                          cam.fov_deg * 3.14159265f / 180.f, o.width, o.height, 0.1f, 2000.f);
  std::vector<crowd::Placement> placements;
  crowd::place_agents(p.scene, 0, placements);
  std::vector<int> out;
  crowd::CutStats stats;
  for (const auto& pl : placements) {
    const auto& ch = *p.characters[static_cast<std::size_t>(pl.character)];
    out.clear();
    crowd::lod_cut(*hierarchies[static_cast<std::size_t>(pl.character)], crowd::placement_transform(pl) * ch.normalize,
                   view, poe, out, stats);
  }
  return static_cast<double>(stats.triangles);
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--scenes") o.scenes = split(v);
    else if (k == "--frames") o.frames = std::stoi(v);
    else if (k == "--nolod-frames") o.nolod_frames = std::stoi(v);
    else if (k == "--width") o.width = std::stoi(v);
    else if (k == "--height") o.height = std::stoi(v);
    else if (k == "--stream-poe") o.stream_poe = std::stof(v);
    else if (k == "--db") o.db = v;
    else if (k == "--max-subdivision") o.max_subdivision = std::stoi(v);
    else if (k == "--data-dir") o.data_dir = v;
    else {
      std::fprintf(stderr, "unknown option %s\n", k.c_str());
      return 2;
    }
  }
  const std::string db_path =
      o.db.empty() ? (std::filesystem::temp_directory_path() / ("crowd_bench_" + std::to_string(getpid()) + ".db")).string()
                   : o.db;
  store::DbPool db(db_path);
  {
    auto conn = db.acquire();
    store::migrate(*conn);
  }
  api::CrowdAssets assets(o.data_dir + "/models", &db, o.max_subdivision);
  render::EglContext context;
  render::CrowdRenderer renderer(context);
  render::JpegEncoder encoder;
  std::printf("crowd bench: %s | %s | %dx%d, %d frames per mode (NoLOD %d), hierarchies cached in %s\n\n",
              context.renderer().c_str(), context.version().c_str(), o.width, o.height, o.frames, o.nolod_frames,
              db_path.c_str());

  std::map<std::string, int> uploaded;
  std::vector<std::pair<std::string, std::unique_ptr<server::PreparedScene>>> scenes;
  for (const auto& id : o.scenes) {
    const auto* spec = crowd::find_scene_spec(id);
    if (!spec) {
      std::fprintf(stderr, "unknown scene %s\n", id.c_str());
      return 2;
    }
    auto progress = [&id](const std::string& stage, const std::string& model, int done, int total) {
      std::fprintf(stderr, "  %s: %s %s (%d/%d)\n", id.c_str(), stage.c_str(), model.c_str(), done, total);
    };
    scenes.emplace_back(id, server::prepare_scene(assets, renderer, uploaded, *spec, spec->default_count, progress));
  }

  // 1. Construction.
  std::printf("## Construction (per character, as the scenes use it)\n\n");
  std::printf("| model | base triangles | vertices | poses | representative | leaf clusters | clusters | stored / base tris | build s | cached | hierarchy B/tri | total B/tri |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|\n");
  std::map<std::string, bool> printed;
  for (const auto& [id, p] : scenes)
    for (const auto& ch : p->characters) {
      if (printed[ch->name]) continue;
      printed[ch->name] = true;
      const auto& h = ch->hierarchy;
      const auto& st = h.stats;
      const double base = static_cast<double>(ch->model.triangle_count());
      const double hier_bytes = static_cast<double>(crowd::serialize_hierarchy(h).size());
      const double vertex_bytes = static_cast<double>(ch->model.vertex_count()) * (12 + 12 + 4 + 8 + 16);
      std::size_t leaves = 0, stored = 0;
      for (const auto& c : h.clusters) {
        leaves += c.is_leaf();
        stored += c.triangle_count();
      }
      const std::size_t poses = ch->model.animations[0].poses.size();
      const std::size_t reps = st.representative_poses_per_animation.empty() ? 0 : st.representative_poses_per_animation[0];
      std::printf("| %s | %.0f | %zu | %zu | %zu | %zu | %zu | %.2f | %.1f | %s | %.1f | %.1f |\n", ch->name.c_str(), base,
                  ch->model.vertex_count(), poses, reps, leaves, h.clusters.size(), stored / base,
                  (ch->load_ms + ch->build_ms) / 1000.0, ch->from_cache ? "yes" : "no", hier_bytes / base,
                  (hier_bytes + vertex_bytes) / base);
    }

  // 2. Error-aware vs octree clusters (office characters, VDR cut at the default camera).
  for (const auto& [id, p] : scenes) {
    if (id != "office" && id != "exhibition") continue;
    std::printf("\n## Error-aware vs octree leaf clusters (%s, %zu characters, VDR cut at the default camera)\n\n", id.c_str(),
                p->scene.agents.size());
    // The same characters clustered by the octree baseline, and with the paper's quadric error
    // radius (sqrt of the max quadric error) instead of the measured Hausdorff distance.
    std::vector<crowd::ClusterHierarchy> octree, quadric;
    std::vector<const crowd::ClusterHierarchy*> aware_h, octree_h, quadric_h;
    octree.reserve(p->characters.size());
    quadric.reserve(p->characters.size());
    double octree_s = 0;
    for (const auto& ch : p->characters) {
      crowd::HierarchyOptions opt;
      opt.clustering = crowd::LeafClustering::octree;
      const auto t0 = Clock::now();
      octree.push_back(crowd::build_vdr_hierarchy(ch->model, opt));
      octree_s += ms_since(t0) / 1000.0;
      crowd::HierarchyOptions q;
      q.error_metric = crowd::ClusterError::quadric;
      quadric.push_back(crowd::build_vdr_hierarchy(ch->model, q));
      aware_h.push_back(&ch->hierarchy);
    }
    for (const auto& h : octree) octree_h.push_back(&h);
    for (const auto& h : quadric) quadric_h.push_back(&h);
    std::printf("| PoE | error-aware triangles | octree triangles | error-aware / octree | error-aware, quadric error radius |\n"
                "|---:|---:|---:|---:|---:|\n");
    for (float poe : {0.5f, 1.f, o.stream_poe, 4.f}) {
      const double a = cut_triangles(*p, aware_h, o, poe), b = cut_triangles(*p, octree_h, o, poe);
      std::printf("| %.1f | %.0f | %.0f | %.2f | %.0f |\n", poe, a, b, b > 0 ? a / b : 0.0,
                  cut_triangles(*p, quadric_h, o, poe));
    }
    std::printf("(octree hierarchies built in %.1f s)\n", octree_s);
    break;  // one scene is enough for the comparison
  }

  // 3. LOD cut time for 1K characters, JPEG encode time.
  for (const auto& [id, p] : scenes) {
    if (p->scene.agents.size() < 1000) continue;
    std::vector<crowd::Placement> placements;
    crowd::place_agents(p->scene, 0, placements);
    placements.resize(1000);
    const auto cam = path_camera(p->scene, 0, o.width, o.height);
    const auto view = render::make_camera_view(cam.eye, cam.target, crowd::Vec3::UnitY(), cam.fov_deg * 3.14159265f / 180.f,
                                               o.width, o.height, 0.1f, 2000.f);
    std::vector<crowd::Affine> worlds;
    for (const auto& pl : placements) {
      worlds.push_back(crowd::placement_transform(pl) * p->characters[static_cast<std::size_t>(pl.character)]->normalize);
    }
    std::vector<crowd::CutTree> trees;
    for (const auto& ch : p->characters) trees.push_back(crowd::build_cut_tree(ch->hierarchy));
    std::vector<crowd::CutInstance> instances;
    for (std::size_t i = 0; i < placements.size(); ++i)
      instances.push_back({&trees[static_cast<std::size_t>(placements[i].character)], &worlds[i]});
    util::ForkJoin pool(2);
    crowd::CutWorkspace workspace;
    struct Variant {
      const char* name;
      int threads;
      std::vector<double> times;
      crowd::CutStats stats;
    };
    std::vector<int> out;
    std::vector<std::size_t> out_begin;
    constexpr int kReps = 200;
    std::printf("\n## LOD cut, 1,000 characters of %s, PoE 0.5 (CPU; %d reps per variant, taking turns)\n\n", id.c_str(),
                kReps);
    std::printf("| view | variant | threads | p50 ms | p99 ms | clusters visited | clusters in cut | frustum-culled | "
                "triangles | speed-up vs baseline (p50) |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    // One table row per variant; the variants take turns rep by rep, so load from other
    // processes hits them alike. Leaves `out` / `out_begin` with the last variant's cuts.
    const auto measure = [&](const char* view_name, const crowd::CameraView& at) {
      std::array<Variant, 3> variants = {Variant{"baseline: recursive walk, world AABB per cluster", 1, {}, {}},
                                         Variant{"cut_instances: flat cut tree, model space, hull early-outs", 1, {}, {}},
                                         Variant{"cut_instances: flat cut tree, model space, hull early-outs", 2, {}, {}}};
      for (int rep = 0; rep < kReps; ++rep) {
        for (std::size_t v = 0; v < variants.size(); ++v) {
          Variant& var = variants[v];
          out.clear();
          var.stats = {};
          const auto t0 = Clock::now();
          if (v == 0) {
            for (std::size_t i = 0; i < placements.size(); ++i)
              baseline::lod_cut(p->characters[static_cast<std::size_t>(placements[i].character)]->hierarchy, worlds[i], at,
                                0.5f, out, var.stats);
          } else {
            crowd::cut_instances(instances, at, 0.5f, var.threads == 2 ? &pool : nullptr, workspace, out, out_begin,
                                 var.stats);
          }
          var.times.push_back(ms_since(t0));
        }
      }
      const double base_p50 = percentile(variants[0].times, 0.5);
      for (const Variant& var : variants) {
        const double p50 = percentile(var.times, 0.5);
        std::printf("| %s | %s | %d | %.3f | %.3f | %zu | %zu | %zu | %zu | %.1fx |\n", view_name, var.name, var.threads, p50,
                    percentile(var.times, 0.99), var.stats.visited, var.stats.drawn, var.stats.frustum_culled,
                    var.stats.triangles, p50 > 0 ? base_p50 / p50 : 0.0);
      }
      return variants[1].stats.visited;
    };
    // A closer view (eye at 40% of the distance to the target) leaves part of the crowd outside
    // the frustum: the case of the culling rule and the per-instance early-outs.
    const crowd::Vec3 close_eye = cam.target + 0.4f * (cam.eye - cam.target);
    const auto close_view = render::make_camera_view(close_eye, cam.target, crowd::Vec3::UnitY(),
                                                     cam.fov_deg * 3.14159265f / 180.f, o.width, o.height, 0.1f, 2000.f);
    measure("close", close_view);
    const std::size_t walk_visited = measure("default", view);
    // Temporal coherence (refine / coarsen last frame's cut where the test flipped) is exact only
    // if the test is monotone down a path (a parent fine enough => its children too), which needs
    // each child's box inside its parent's: then a cut cluster is confirmed by testing itself and
    // its parent. Counted here: children sticking out, pairs that break monotonicity at this view,
    // and the least such an update must test (each cut cluster and its distinct parents) against
    // what the walk visits (each cut cluster and all its ancestors).
    std::size_t children = 0, sticking_out = 0;
    for (const auto& ch : p->characters)
      for (const auto& c : ch->hierarchy.clusters)
        for (int child : c.children) {
          if (child < 0) continue;
          ++children;
          sticking_out += !c.bounds.contains(ch->hierarchy.clusters[static_cast<std::size_t>(child)].bounds);
        }
    const crowd::CutFrame frame = crowd::make_cut_frame(view, 0.5f);
    std::size_t pairs = 0, flipped = 0;
    for (const crowd::CutInstance& inst : instances) {
      const crowd::Vec3 eye = inst.world->inverse() * frame.eye;
      const auto fine = [&](const crowd::CutNode& c) {
        const crowd::Vec3 d = ((eye - crowd::Vec3(c.center[0], c.center[1], c.center[2])).cwiseAbs() -
                               crowd::Vec3(c.half[0], c.half[1], c.half[2]))
                                  .cwiseMax(0.f);
        return c.error_sq * frame.k_sq <= d.squaredNorm();
      };
      const auto& nodes = inst.tree->nodes;
      for (std::size_t i = 0; i < nodes.size(); ++i) {
        if (nodes[i].error_sq < 0) continue;  // a leaf
        for (const std::size_t child : {i + 1, std::size_t{nodes[i + 1].skip}}) {
          ++pairs;
          flipped += fine(nodes[i]) && !fine(nodes[child]);
        }
      }
    }
    std::size_t least_coherent = 0;  // out / out_begin hold the last variant's cuts
    for (std::size_t i = 0; i < placements.size(); ++i) {
      const auto& h = p->characters[static_cast<std::size_t>(placements[i].character)]->hierarchy;
      std::vector<int> parents;
      for (std::size_t k = out_begin[i]; k < out_begin[i + 1]; ++k)
        if (const int parent = h.clusters[static_cast<std::size_t>(out[k])].parent; parent >= 0) parents.push_back(parent);
      std::sort(parents.begin(), parents.end());
      least_coherent += (out_begin[i + 1] - out_begin[i]) +
                        static_cast<std::size_t>(std::unique(parents.begin(), parents.end()) - parents.begin());
    }
    std::printf("(temporal coherence, default view: child boxes not inside their parent's: %zu of %zu; parent fine enough but child not "
                "at this view: %zu of %zu pairs; an exact coherent update tests >= %zu clusters, the walk %zu)\n",
                sticking_out, children, flipped, pairs, least_coherent, walk_visited);
    break;
  }
  {
    const auto& p = *scenes.front().second;
    std::vector<std::uint8_t> rgba;
    std::vector<crowd::Placement> scratch;
    render::FrameRequest req;
    server::scene_frame_request(p, 0, path_camera(p.scene, 0, o.width, o.height), render::RenderMode::vdr, 0.5f, false,
                                req, scratch);
    render::FrameStats fs{};
    renderer.render(req, rgba, fs);
    std::printf("\n## JPEG encode (%s frame, %dx%d)\n\n| quality | ms p50 | KiB |\n|---:|---:|---:|\n", scenes.front().first.c_str(),
                o.width, o.height);
    for (int q : {50, 75, 90}) {
      std::vector<double> times;
      std::size_t bytes = 0;
      for (int rep = 0; rep < 20; ++rep) {
        const auto t0 = Clock::now();
        bytes = encoder.encode_rgba(rgba.data(), o.width, o.height, q, true).size();
        times.push_back(ms_since(t0));
      }
      std::printf("| %d | %.2f | %.1f |\n", q, percentile(times, 0.5), bytes / 1024.0);
    }
  }

  // 4. Table 3.1.
  std::printf("\n## Table 3.1 on this machine (%dx%d; fps = frames / render time incl. LOD cut and readback)\n\n", o.width,
              o.height);
  std::printf("| scene | characters | full-res triangles | PoE | NoLOD fps | VDR fps | VDR+OC fps | NoLOD tris | VDR tris | VDR+OC tris | VDR+OC occluded | LOD cut ms | VDR+OC / NoLOD |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& [id, p] : scenes) {
    std::fprintf(stderr, "  %s: NoLOD...\n", id.c_str());
    const ModeResult nolod = run_mode(renderer, *p, render::RenderMode::no_lod, 0, o.nolod_frames, o);
    for (float poe : {0.5f, o.stream_poe}) {
      std::fprintf(stderr, "  %s: PoE %.1f VDR, VDR+OC...\n", id.c_str(), poe);
      const ModeResult vdr = run_mode(renderer, *p, render::RenderMode::vdr, poe, o.frames, o);
      const ModeResult oc = run_mode(renderer, *p, render::RenderMode::vdr_oc, poe, o.frames, o);
      std::printf("| %s | %zu | %.2f M | %.1f | %.2f | %.2f | %.2f | %.2f M | %.2f M | %.2f M | %.0f | %.2f | %.1fx |\n", id.c_str(),
                  p->scene.agents.size(), static_cast<double>(p->full_triangles) / 1e6, poe, nolod.fps, vdr.fps, oc.fps,
                  nolod.triangles / 1e6, vdr.triangles / 1e6, oc.triangles / 1e6, oc.occluded, vdr.lod_cut_ms,
                  nolod.fps > 0 ? oc.fps / nolod.fps : 0.0);
    }
  }
  if (o.db.empty()) std::filesystem::remove(db_path);
  return 0;
}
