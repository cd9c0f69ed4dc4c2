#include "export/svg_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace tourmap::map_export {
namespace {

using geo::XY;

// A number with at most two decimals, no trailing zeros ("12", "3.5", "-0.25").
void num(std::string& out, double v) {
  if (!std::isfinite(v)) v = 0;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  std::string s(buf);
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  out += s;
}

void attr(std::string& out, const char* name, double v) {
  out += ' ';
  out += name;
  out += "=\"";
  num(out, v);
  out += '"';
}

void attr(std::string& out, const char* name, const std::string& v) {
  out += ' ';
  out += name;
  out += "=\"";
  out += xml_escape(v);
  out += '"';
}

std::string hex(const Color& c) {
  auto channel = [](double v) { return static_cast<int>(std::lround(std::clamp(v, 0.0, 1.0) * 255)); };
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", channel(c.r), channel(c.g), channel(c.b));
  return buf;
}

void paint(std::string& out, const char* what, const Color& c) {
  attr(out, what, hex(c));
  if (c.a < 1) attr(out, (std::string(what) + "-opacity").c_str(), c.a);
}

const char* role_name(Role r) {
  switch (r) {
    case Role::background: return "background";
    case Role::title: return "title";
    case Role::casing: return "casing";
    case Role::line: return "line";
    case Role::station: return "station";
    case Role::label: return "station-label";
    case Role::legend: return "legend";
    case Role::attribution: return "attribution";
  }
  return "";
}

void write(std::string& out, const Strokes& s) {
  out += "<path";
  attr(out, "class", role_name(s.role));
  out += " fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\"";
  paint(out, "stroke", s.color);
  attr(out, "stroke-width", s.width);
  out += " d=\"";
  for (const auto& path : s.paths) {
    for (std::size_t i = 0; i < path.size(); ++i) {
      out += i == 0 ? 'M' : 'L';
      num(out, path[i].x);
      out += ' ';
      num(out, path[i].y);
    }
  }
  out += "\"/>\n";
}

void write(std::string& out, const RoundedRect& r) {
  out += "<rect";
  attr(out, "class", role_name(r.role));
  const bool placed = r.angle_deg != 0;
  attr(out, "x", placed ? -r.width / 2 : r.center.x - r.width / 2);
  attr(out, "y", placed ? -r.height / 2 : r.center.y - r.height / 2);
  attr(out, "width", r.width);
  attr(out, "height", r.height);
  if (r.radius > 0) attr(out, "rx", r.radius);
  if (placed) {
    std::string t = "translate(";
    num(t, r.center.x);
    t += ' ';
    num(t, r.center.y);
    t += ") rotate(";
    num(t, r.angle_deg);
    t += ')';
    attr(out, "transform", t);
  }
  paint(out, "fill", r.fill);
  if (r.stroke_width > 0) {
    paint(out, "stroke", r.stroke);
    attr(out, "stroke-width", r.stroke_width);
  }
  out += "/>\n";
}

void write(std::string& out, const Text& t) {
  out += "<text";
  attr(out, "class", role_name(t.role));
  attr(out, "x", t.at.x);
  attr(out, "y", t.at.y);
  attr(out, "font-size", t.size_px);
  if (t.bold) out += " font-weight=\"bold\"";
  if (t.anchor != 's') out += t.anchor == 'm' ? " text-anchor=\"middle\"" : " text-anchor=\"end\"";
  paint(out, "fill", t.fill);
  if (t.halo_px > 0) {
    paint(out, "stroke", t.halo);
    attr(out, "stroke-width", t.halo_px);
    out += " stroke-linejoin=\"round\" paint-order=\"stroke\"";
  }
  out += '>';
  for (std::size_t i = 0; i < t.lines.size(); ++i) {
    out += "<tspan";
    attr(out, "x", t.at.x);
    if (i > 0) attr(out, "dy", t.line_px);
    if (i < t.fit_em.size() && t.fit_em[i] > 0) {
      attr(out, "textLength", t.fit_em[i] * t.size_px);
      out += " lengthAdjust=\"spacingAndGlyphs\"";
    }
    out += '>';
    out += xml_escape(t.lines[i]);
    out += "</tspan>";
  }
  out += "</text>\n";
}

}  // namespace

std::string xml_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 && c != '\t' && c != '\n' && c != '\r') continue;
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string write_svg(const Drawing& d, const SvgSize& size) {
  std::string out;
  out.reserve(4096 + d.items.size() * 160);
  out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\"";
  if (size.width.empty()) attr(out, "width", d.width); else attr(out, "width", size.width);
  if (size.height.empty()) attr(out, "height", d.height); else attr(out, "height", size.height);
  std::string box = "0 0 ";
  num(box, d.width);
  box += ' ';
  num(box, d.height);
  attr(out, "viewBox", box);
  // The labels' font first; fallbacks are stretched to its widths (textLength).
  attr(out, "font-family", "'" + d.font_family + "', 'DejaVu Sans', 'Arial Narrow', sans-serif");
  out += ">\n<title>";
  out += xml_escape(d.title);
  out += "</title>\n";
  for (const auto& item : d.items) std::visit([&](const auto& p) { write(out, p); }, item);
  out += "</svg>\n";
  return out;
}

}  // namespace tourmap::map_export
