// POI imports (core/load/poi_load: load_pois, as the importer calls it): the format is picked
// from the extension and the content, so the first input byte picks the file name
// (.csv, .json, .geojson, .js) and the rest is the file. Clean error: load::LoadError.

#include "fuzz_common.hpp"

#include "load/load_error.hpp"
#include "load/poi_load.hpp"

#include <cmath>
#include <set>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tourmap;
  if (size < 1) return 0;
  static const char* const names[] = {"pois.csv", "pois.json", "pois.geojson", "pois.js"};
  const char* name = names[data[0] % 4];
  const std::string path = fuzz::ScratchDir::get().write(name, fuzz::as_view(data + 1, size - 1));
  try {
    const auto pois = load::load_pois(path, {"sight"});
    // Promised per record: a name, a valid position, a unique id.
    std::set<std::string> ids;
    for (const auto& p : pois) {
      FUZZ_CHECK(!p.name.empty() && geo::is_valid(p.pos));
      FUZZ_CHECK(ids.insert(p.id).second);
      FUZZ_CHECK(!p.rank || std::isfinite(*p.rank));
      FUZZ_CHECK(!p.popularity || std::isfinite(*p.popularity));
    }
  } catch (const load::LoadError&) {
  }
  return 0;
}
