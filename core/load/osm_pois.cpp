#include "load/osm_pois.hpp"

#include "geo/projection.hpp"
#include "load/file.hpp"
#include "load/load_error.hpp"
#include "load/osm_input.hpp"
#include "load/strings.hpp"
#include "util/stop.hpp"

#include <osmium/handler.hpp>
#include <osmium/handler/node_locations_for_ways.hpp>
#include <osmium/index/map/flex_mem.hpp>
#include <osmium/io/any_input.hpp>
#include <osmium/visitor.hpp>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <unordered_map>

namespace tourmap::load {
namespace {

using LocationIndex = osmium::index::map::FlexMem<osmium::unsigned_object_id_type, osmium::Location>;
using LocationHandler = osmium::handler::NodeLocationsForWays<LocationIndex>;

constexpr double kSameNameMetres = 200;      // a node and a way of one name this close: one place
constexpr double kSameWikidataMetres = 1000;  // with one wikidata item

bool is_any(const char* value, std::initializer_list<const char*> expected) {
  return value &&
         std::any_of(expected.begin(), expected.end(), [&](const char* e) { return std::strcmp(value, e) == 0; });
}

// The category of a kept entity (the table in osm_pois.hpp), or none.
std::optional<std::string> category_of(const osmium::TagList& tags) {
  const char* tourism = tag_value(tags, "tourism");
  if (is_any(tourism, {"attraction", "museum", "gallery", "viewpoint", "zoo", "theme_park", "aquarium"})) return tourism;
  const char* historic = tag_value(tags, "historic");
  if (historic && *historic && !is_any(historic, {"no", "yes"})) return historic;
  const char* amenity = tag_value(tags, "amenity");
  if (is_any(amenity, {"theatre", "arts_centre"})) return amenity;
  if (is_any(amenity, {"place_of_worship"}) && (tag_value(tags, "wikidata") || tag_value(tags, "wikipedia")))
    return amenity;
  return std::nullopt;
}

// "theme_park" -> "theme park".
std::string as_words(std::string value) {
  std::replace(value.begin(), value.end(), '_', ' ');
  return value;
}

bool is_http(const char* url) { return url && (std::strncmp(url, "http://", 7) == 0 || std::strncmp(url, "https://", 8) == 0); }

// Characters of a URL path segment kept as they are; the rest percent-encoded (spaces as _ for
// Wikipedia titles and Commons file names, as those sites write them).
std::string url_segment(std::string_view text) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  for (const unsigned char c : text) {
    if (c == ' ') out += '_';
    else if (std::isalnum(c) || std::strchr("-_.~()',!*:", c)) out += static_cast<char>(c);
    else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

// "de:Vaduz" -> https://de.wikipedia.org/wiki/Vaduz (a language code of 2-12 letters and dashes).
std::string wikipedia_url(const char* tag) {
  if (!tag) return {};
  if (is_http(tag)) return tag;
  const char* colon = std::strchr(tag, ':');
  if (!colon || colon == tag || colon - tag > 12 || !colon[1]) return {};
  for (const char* c = tag; c < colon; ++c)
    if (!std::isalpha(static_cast<unsigned char>(*c)) && *c != '-') return {};
  return "https://" + std::string(tag, colon) + ".wikipedia.org/wiki/" + url_segment(colon + 1);
}

// "Q1234" -> https://www.wikidata.org/wiki/Q1234.
std::string wikidata_url(const char* tag) {
  if (!tag || tag[0] != 'Q' || !tag[1]) return {};
  for (const char* c = tag + 1; *c; ++c)
    if (!std::isdigit(static_cast<unsigned char>(*c))) return {};
  return std::string("https://www.wikidata.org/wiki/") + tag;
}

std::string image_url(const osmium::TagList& tags) {
  if (const char* image = tag_value(tags, "image"); is_http(image)) return image;
  const char* commons = tag_value(tags, "wikimedia_commons");
  if (commons && std::strncmp(commons, "File:", 5) == 0 && commons[5])
    return "https://commons.wikimedia.org/wiki/Special:FilePath/" + url_segment(commons + 5);
  return {};
}

double popularity_of(const osmium::TagList& tags, const std::string& category) {
  double score = 0;
  if (wikidata_url(tag_value(tags, "wikidata")).size()) score += 2;
  if (wikipedia_url(tag_value(tags, "wikipedia")).size()) score += 2;
  if (const char* heritage = tag_value(tags, "heritage"); heritage && *heritage && std::strcmp(heritage, "no") != 0)
    score += is_any(heritage, {"1", "2"}) ? 2 : 1;
  score += is_any(category.c_str(), {"museum", "castle", "zoo", "theme_park", "aquarium", "attraction"}) ? 1 : 0.5;
  return score;
}

struct Found {
  model::Poi poi;
  std::string wikidata;  // the item id, for merging
  bool from_way = false;
};

class PoiCollector : public osmium::handler::Handler {
 public:
  PoiCollector(OsmPoiStats& stats, const ImportLimits& limits, const std::string& source)
      : stats_(stats), limits_(limits), source_(source) {}

  void node(const osmium::Node& node) {
    ++stats_.osm_nodes;
    check_limit(stats_.osm_nodes, limits_.max_osm_nodes, "max_osm_nodes", where(), "nodes in the file");
    tick();
    if (node.tags().empty()) return;
    if (!well_formed_tags(node.tags())) {
      ++stats_.malformed_tags;
      return;
    }
    if (!node.location().valid()) return;
    add(node.tags(), "n" + std::to_string(node.id()), {node.location().lon(), node.location().lat()}, false);
  }

  void way(const osmium::Way& way) {
    ++stats_.osm_ways;
    check_limit(stats_.osm_ways, limits_.max_osm_ways, "max_osm_ways", where(), "ways in the file");
    tick();
    if (way.tags().empty()) return;
    if (!well_formed_tags(way.tags())) {
      ++stats_.malformed_tags;
      return;
    }
    if (!category_of(way.tags())) return;
    const auto centre = way_centre(way);
    if (!centre) {
      ++stats_.no_location;
      return;
    }
    add(way.tags(), "w" + std::to_string(way.id()), *centre, true);
  }

  void relation(const osmium::Relation& relation) {
    if (well_formed_tags(relation.tags()) && category_of(relation.tags())) ++stats_.relations_skipped;
  }

  // Way places merged into a place found before them (nodes first, then ways in file order)
  // of the same name nearby or with the same wikidata item.
  std::vector<model::Poi> finish() && {
    std::vector<bool> gone(found_.size(), false);
    std::unordered_map<std::string, std::vector<std::size_t>> by_name, by_wikidata;
    const auto remember = [&](std::size_t i) {
      by_name[ascii_lower(found_[i].poi.name)].push_back(i);
      if (!found_[i].wikidata.empty()) by_wikidata[found_[i].wikidata].push_back(i);
    };
    for (std::size_t i = 0; i < found_.size(); ++i)
      if (!found_[i].from_way) remember(i);
    const auto near = [&](std::size_t a, std::size_t b, double metres) {
      return geo::geodesic_distance_m(found_[a].poi.pos, found_[b].poi.pos) <= metres;
    };
    for (std::size_t i = 0; i < found_.size(); ++i) {
      if (!found_[i].from_way) continue;
      std::optional<std::size_t> into;
      if (auto it = by_wikidata.find(found_[i].wikidata); !found_[i].wikidata.empty() && it != by_wikidata.end())
        for (auto j : it->second)
          if (!into && near(i, j, kSameWikidataMetres)) into = j;
      if (auto it = by_name.find(ascii_lower(found_[i].poi.name)); !into && it != by_name.end())
        for (auto j : it->second)
          if (!into && near(i, j, kSameNameMetres)) into = j;
      if (!into) {
        remember(i);
        continue;
      }
      auto& keep = found_[*into].poi;
      const auto& from = found_[i].poi;
      if (keep.url.empty()) keep.url = from.url;
      if (keep.wikipedia.empty()) keep.wikipedia = from.wikipedia;
      if (keep.image_url.empty()) keep.image_url = from.image_url;
      keep.popularity = std::max(keep.popularity.value_or(0), from.popularity.value_or(0));
      gone[i] = true;
      ++stats_.merged;
      --stats_.from_ways;
    }
    std::vector<model::Poi> out;
    out.reserve(found_.size());
    for (std::size_t i = 0; i < found_.size(); ++i)
      if (!gone[i]) out.push_back(std::move(found_[i].poi));
    return out;
  }

  std::string where() const {
    return source_ + " after " + std::to_string(stats_.osm_nodes) + " nodes and " + std::to_string(stats_.osm_ways) + " ways";
  }

 private:
  void tick() {
    if (((stats_.osm_nodes + stats_.osm_ways) & 8191) == 0) util::check_stop();
  }

  void add(const osmium::TagList& tags, std::string id, geo::LonLat pos, bool from_way) {
    const auto category = category_of(tags);
    if (!category) return;
    const char* name = tag_value(tags, "name");
    if (!name || !*name) {
      ++stats_.unnamed;
      return;
    }
    const std::string at = source_ + " " + (from_way ? "way " : "node ") + id.substr(1);
    check_text(name, limits_.max_name_bytes, "max_name_bytes", at, "name tag");
    check_limit(found_.size() + 1, limits_.max_pois, "max_pois", at, "POIs");
    Found f;
    f.poi.id = std::move(id);
    f.poi.name = name;
    f.poi.pos = pos;
    f.poi.category = as_words(*category);
    const char* website = tag_value(tags, "website");
    if (!is_http(website)) website = tag_value(tags, "contact:website");
    if (!is_http(website)) website = tag_value(tags, "url");
    if (is_http(website)) f.poi.url = website;
    const char* wikidata = tag_value(tags, "wikidata");
    f.poi.wikipedia = wikipedia_url(tag_value(tags, "wikipedia"));
    if (f.poi.wikipedia.empty()) f.poi.wikipedia = wikidata_url(wikidata);
    if (!wikidata_url(wikidata).empty()) f.wikidata = wikidata;
    f.poi.image_url = image_url(tags);
    for (const auto* url : {&f.poi.url, &f.poi.wikipedia, &f.poi.image_url})
      check_text(*url, limits_.max_url_bytes, "max_url_bytes", at, "link");
    f.poi.popularity = popularity_of(tags, *category);
    f.from_way = from_way;
    ++(from_way ? stats_.from_ways : stats_.from_nodes);
    found_.push_back(std::move(f));
  }

  OsmPoiStats& stats_;
  const ImportLimits& limits_;
  const std::string& source_;
  std::vector<Found> found_;
};

}  // namespace

bool is_osm_file_name(const std::string& name) {
  auto ends_with = [&](std::string_view suffix) {
    return name.size() >= suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  return ends_with(".osm") || ends_with(".osm.gz") || ends_with(".osm.bz2") || ends_with(".pbf");
}

std::vector<model::Poi> load_osm_pois(const std::string& path, OsmPoiStats* stats_out, const ImportLimits& limits) {
  if (!std::filesystem::is_regular_file(path)) throw LoadError(path, "no such file");
  const std::string source = file_name(path);
  OsmPoiStats stats;
  PoiCollector collector(stats, limits, source);
  try {
    const OsmInput input(path, limits, source);
    util::check_stop();
    osmium::io::Reader reader(input.file(), osmium::osm_entity_bits::nwr);
    LocationIndex index;
    LocationHandler locations(index);
    locations.ignore_errors();  // ways may reference nodes outside the extract
    while (osmium::memory::Buffer buffer = reader.read()) {
      util::check_stop();
      osmium::apply(buffer, locations, collector);
    }
    reader.close();
    auto pois = std::move(collector).finish();
    if (stats_out) *stats_out = stats;
    return pois;
  } catch (const LoadError&) {
    throw;  // LimitExceeded included
  } catch (const util::Stopped&) {
    throw;
  } catch (const std::exception& e) {
    throw LoadError(collector.where(), std::string("cannot read OSM data: ") + e.what());
  }
}

}  // namespace tourmap::load
