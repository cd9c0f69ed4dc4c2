#include "positions_binary.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cstring>
#include <limits>

namespace tourmap::api {
namespace {

static_assert(std::endian::native == std::endian::little, "the binary positions are written little-endian as in memory");

template <class T>
void put(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

bool iequals(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

// The q of one media range ("type/subtype;q=0.5;..."): 1 unless given; 0 when malformed.
double quality_of(std::string_view params) {
  double q = 1;
  while (!params.empty()) {
    const auto semi = params.find(';');
    const auto param = trim(params.substr(0, semi));
    params = semi == std::string_view::npos ? std::string_view{} : params.substr(semi + 1);
    if (param.size() < 2 || (param[0] | 0x20) != 'q' || param[1] != '=') continue;
    const auto v = param.substr(2);
    // RFC 9110 qvalue: 0, 0.x{0,3}, 1, 1.0{0,3}.
    if (v.empty() || v.size() > 5 || (v[0] != '0' && v[0] != '1') || (v.size() > 1 && v[1] != '.')) return 0;
    double value = v[0] - '0', scale = 0.1;
    for (std::size_t i = 2; i < v.size(); ++i, scale /= 10) {
      if (v[i] < '0' || v[i] > '9') return 0;
      value += (v[i] - '0') * scale;
    }
    q = std::min(value, 1.0);
  }
  return q;
}

}  // namespace

std::string encode_positions_binary(std::string_view json, const std::vector<geo::LonLat>& points) {
  double west = std::numeric_limits<double>::infinity(), east = -west, south = west, north = -west;
  for (const auto& p : points) {
    west = std::min(west, p.lon), east = std::max(east, p.lon);
    south = std::min(south, p.lat), north = std::max(north, p.lat);
  }
  const double lon0 = points.empty() ? 0.0 : (west + east) / 2, lat0 = points.empty() ? 0.0 : (south + north) / 2;
  std::string out;
  out.reserve(32 + json.size() + 3 + 8 * points.size());
  out.append(kPositionsMagic, 4);
  put(out, kPositionsVersion);
  put(out, static_cast<std::uint32_t>(json.size()));
  put(out, static_cast<std::uint32_t>(points.size()));
  put(out, lon0);
  put(out, lat0);
  out.append(json);
  out.append((4 - out.size() % 4) % 4, '\0');
  for (const auto& p : points) {
    put(out, static_cast<float>(p.lon - lon0));
    put(out, static_cast<float>(p.lat - lat0));
  }
  return out;
}

bool accepts_octet_stream(std::string_view accept) {
  double octet = 0, json = -1;
  while (!accept.empty()) {
    const auto comma = accept.find(',');
    const auto range = trim(accept.substr(0, comma));
    accept = comma == std::string_view::npos ? std::string_view{} : accept.substr(comma + 1);
    const auto semi = range.find(';');
    const auto type = trim(range.substr(0, semi));
    const double q = quality_of(semi == std::string_view::npos ? std::string_view{} : range.substr(semi + 1));
    if (iequals(type, "application/octet-stream")) octet = std::max(octet, q);
    else if (iequals(type, "application/json")) json = std::max(json, q);
  }
  return octet > 0 && octet >= json;
}

}  // namespace tourmap::api
