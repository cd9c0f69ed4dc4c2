#include "json_out.hpp"

#include "load/text_repair.hpp"

#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <cstdio>

namespace tourmap::api {

void append_number(std::string& out, double value) {
  if (!std::isfinite(value)) {
    out += "null";
    return;
  }
  // Fixed point with 7 decimals via an integer of 1e-7 units: several times faster than
  // formatting the double (this runs 100K times per deformation response).
  double scaled = std::round(value * 1e7);
  if (std::abs(scaled) >= 9e15) {  // beyond exact integers: not a coordinate
    out += nlohmann::json(value).dump();
    return;
  }
  auto units = static_cast<std::int64_t>(scaled);
  if (units == 0) {
    out += '0';
    return;
  }
  if (units < 0) {
    out += '-';
    units = -units;
  }
  char digits[24];
  auto [end, ec] = std::to_chars(digits, digits + sizeof digits, units);
  int n = static_cast<int>(end - digits);
  // Split into integer part and 7 decimals (left-padded with zeros).
  if (n <= 7) {
    out += "0.";
    out.append(static_cast<std::size_t>(7 - n), '0');
    out.append(digits, end);
  } else {
    out.append(digits, end - 7);
    out += '.';
    out.append(end - 7, end);
  }
  while (out.back() == '0') out.pop_back();
  if (out.back() == '.') out.pop_back();
}

void append_integer(std::string& out, std::int64_t value) {
  char buf[24];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, value);
  out.append(buf, end);
}

void append_double(std::string& out, double value) {
  if (!std::isfinite(value)) {
    out += "null";
    return;
  }
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, value);  // shortest round trip
  const std::string_view text(buf, static_cast<std::size_t>(end - buf));
  out += text;
  if (text.find_first_of(".e") == std::string_view::npos) out += ".0";
}

namespace {

void append_escaped(std::string& out, unsigned char c) {
  switch (c) {
    case '"': out += "\\\""; break;
    case '\\': out += "\\\\"; break;
    case '\n': out += "\\n"; break;
    case '\r': out += "\\r"; break;
    case '\t': out += "\\t"; break;
    default: {
      char esc[8];
      std::snprintf(esc, sizeof esc, "\\u%04x", c);
      out += esc;
    }
  }
}

}  // namespace

void append_string(std::string& out, std::string_view text) {
  // One pass that copies runs of plain bytes at once; UTF-8 is validated only when the text has
  // a non-ASCII byte (POI names and links are mostly ASCII), and invalid text is written again
  // by nlohmann::json, which replaces the bad bytes.
  const std::size_t start = out.size();
  unsigned char seen = 0;
  std::size_t run = 0;
  out += '"';
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    seen |= c;
    if (c >= 0x20 && c != '"' && c != '\\') continue;
    out.append(text.data() + run, i - run);
    append_escaped(out, c);
    run = i + 1;
  }
  out.append(text.data() + run, text.size() - run);
  out += '"';
  if ((seen & 0x80) && !load::is_valid_utf8(text)) {
    out.resize(start);
    out += nlohmann::json(std::string(text)).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  }
}

void append_position(std::string& out, geo::LonLat p) {
  out += '[';
  append_number(out, p.lon);
  out += ',';
  append_number(out, p.lat);
  out += ']';
}

void append_flat_positions(std::string& out, const std::vector<geo::LonLat>& points) {
  out.reserve(out.size() + points.size() * 24);
  out += '[';
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (i) out += ',';
    append_number(out, points[i].lon);
    out += ',';
    append_number(out, points[i].lat);
  }
  out += ']';
}

}  // namespace tourmap::api
