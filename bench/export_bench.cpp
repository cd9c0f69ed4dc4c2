// Map export benchmark (issue 14, part 7): per shared network, the time to draw the whole
// schematic from its cached layout as GET .../map.{svg,pdf,png} does (api/map_export.cpp):
// reading the layout answer into a scene, laying out the page and drawing it, then writing
// SVG, PDF and PNG, on A3 landscape with the PNG at 300 dpi (4961 x 3508 px); and the files'
// sizes. The sample manifest's metro networks and POIs are imported into a temporary database
// and each default layout (solver=auto: the fast layout the endpoint answers with first) is
// computed once, outside the timings. Times are the best of --runs (default 3), one thread.
//
//   build/bench/export_bench [--data-dir DIR] [--runs N] [--dpi DPI] [--write DIR]
//
// --write DIR saves each city's files there (DIR/<city>.svg, .pdf, .png) for a look.

#include "api/catalog.hpp"
#include "api/map_export.hpp"
#include "api/map_scene_json.hpp"
#include "api/metro_service.hpp"
#include "export/cairo_render.hpp"
#include "export/map_drawing.hpp"
#include "export/svg_writer.hpp"
#include "load/file.hpp"
#include "store/db_pool.hpp"
#include "store/importer.hpp"
#include "store/manifest.hpp"
#include "store/migrate.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>

#include <unistd.h>

namespace {

using namespace tourmap;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// The best of `runs` timings of f; `out` keeps the last result.
template <class T>
double best_ms(int runs, const std::function<T()>& f, T& out) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < runs; ++i) {
    const auto t = Clock::now();
    out = f();
    best = std::min(best, ms_since(t));
  }
  return best;
}

void save(const std::string& dir, const std::string& name, const std::string& bytes) {
  if (dir.empty()) return;
  std::ofstream(dir + "/" + name, std::ios::binary) << bytes;
}

api::Request query(std::map<std::string, std::string> q) {
  api::Request r;
  r.query = std::move(q);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  std::string data_dir = TOURMAP_DEFAULT_DATA_DIR, write_dir;
  if (const char* env = std::getenv("TOURMAP_DATA_DIR")) data_dir = env;
  int runs = 3;
  std::string dpi = "300";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--data-dir") data_dir = argv[i + 1];
    else if (flag == "--runs") runs = std::max(1, std::atoi(argv[i + 1]));
    else if (flag == "--dpi") dpi = argv[i + 1];
    else if (flag == "--write") write_dir = argv[i + 1];
  }
  if (!write_dir.empty()) std::filesystem::create_directories(write_dir);

  // The sample networks and POIs in a temporary database, as `tourmap import manifest` does.
  const auto tmp = std::filesystem::temp_directory_path() / ("tourmap-export-bench-" + std::to_string(::getpid()));
  std::filesystem::create_directories(tmp);
  auto manifest = store::parse_manifest(load::read_file(TOURMAP_MANIFEST), data_dir);
  manifest.roads.clear();
  store::DbPool pool((tmp / "bench.db").string());
  {
    auto db = pool.acquire();
    store::migrate(*db);
    store::run_manifest(*db, manifest, false, [](const store::ImportResult&) {});
  }
  api::Catalog catalog(pool);
  api::MetroService metro(catalog);

  const auto svg_page = api::parse_map_page(query({{"paper", "a3"}}), api::MapFormat::svg);
  const auto pdf_page = api::parse_map_page(query({{"paper", "a3"}}), api::MapFormat::pdf);
  const auto png_page = api::parse_map_page(query({{"paper", "a3"}, {"dpi", dpi}}), api::MapFormat::png);

  std::printf("# tourmap map export benchmark\n\n");
  std::printf("A3 landscape (%.0f x %.0f CSS px), PNG at %s dpi (%.0f x %.0f px); default layout (solver=auto, "
              "fast). Scene: the layout answer's JSON read into the scene; draw: page layout and drawing. Best of %d "
              "runs, ms; sizes in KB.\n\n",
              svg_page.page_width, svg_page.page_height, dpi.c_str(), png_page.out_width, png_page.out_height, runs);
  std::printf("| network | stations | lines | names shown | px/m | scene ms | draw ms | SVG ms | SVG KB | PDF ms | PDF KB | PNG ms | PNG KB |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& m : manifest.metros) {
    const auto data = metro.data_for(m.city.id);
    bool cached = false;
    const auto layout = metro.layout_for(*data, api::LayoutRequest{}, &cached);
    map_export::MapScene scene;
    const double scene_ms = best_ms<map_export::MapScene>(
        runs, [&] { return api::scene_from_layout(nlohmann::json::parse(layout->body), data->city->info.name); }, scene);
    map_export::Drawing drawing;
    const double draw_ms = best_ms<map_export::Drawing>(
        runs, [&] { return map_export::draw_map(scene, svg_page.page_width, svg_page.page_height); }, drawing);
    const auto page = map_export::layout_page(scene, svg_page.page_width, svg_page.page_height);
    std::string svg, pdf, png;
    const double svg_ms = best_ms<std::string>(runs, [&] { return map_export::write_svg(drawing, {svg_page.svg_width, svg_page.svg_height}); }, svg);
    const double pdf_ms = best_ms<std::string>(runs, [&] { return map_export::render_pdf(drawing, pdf_page.out_width, pdf_page.out_height); }, pdf);
    const double png_ms = best_ms<std::string>(
        runs, [&] { return map_export::render_png(drawing, static_cast<int>(png_page.out_width), static_cast<int>(png_page.out_height)); }, png);
    std::size_t stations = 0;
    for (const auto& n : scene.nodes) stations += n.station;
    const std::size_t named = page.label_scale < 0 ? 0 : scene.label_scales[static_cast<std::size_t>(page.label_scale)].labels.size();
    std::printf("| %s | %zu | %zu | %zu | %.3f | %.1f | %.1f | %.1f | %.0f | %.1f | %.0f | %.0f | %.0f |\n", m.city.id.c_str(),
                stations, scene.lines.size(), named, page.fit.scale, scene_ms, draw_ms, svg_ms, svg.size() / 1024.0, pdf_ms,
                pdf.size() / 1024.0, png_ms, png.size() / 1024.0);
    std::fflush(stdout);
    save(write_dir, m.city.id + ".svg", svg);
    save(write_dir, m.city.id + ".pdf", pdf);
    save(write_dir, m.city.id + ".png", png);
  }
  metro.stop_improvements();
  std::filesystem::remove_all(tmp);
  return 0;
}
