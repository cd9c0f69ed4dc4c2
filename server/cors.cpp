#include "cors.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace tourmap::server {
namespace {

std::string normalize(std::string_view s) {
  auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  std::string out = b == std::string_view::npos ? std::string() : std::string(s.substr(b, e - b + 1));
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (out.size() > 1 && out.back() == '/') out.pop_back();
  return out;
}

// scheme://host[:port] with nothing after the authority.
bool is_origin(const std::string& s) {
  auto sep = s.find("://");
  if (sep == std::string::npos || sep == 0) return false;
  if (!std::isalpha(static_cast<unsigned char>(s[0]))) return false;
  for (std::size_t i = 0; i < sep; ++i) {
    char c = s[i];
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '.') return false;
  }
  auto authority = s.substr(sep + 3);
  if (authority.empty()) return false;
  for (char c : authority)
    if (c == '/' || c == '?' || c == '#' || c == '@' || c == ',' || std::isspace(static_cast<unsigned char>(c)) ||
        std::iscntrl(static_cast<unsigned char>(c)))
      return false;
  return true;
}

}  // namespace

CorsPolicy::CorsPolicy(std::string_view origins) {
  std::size_t pos = 0;
  while (pos <= origins.size()) {
    auto comma = origins.find(',', pos);
    if (comma == std::string_view::npos) comma = origins.size();
    auto entry = normalize(origins.substr(pos, comma - pos));
    pos = comma + 1;
    if (entry.empty()) continue;
    if (entry == "*") {
      any_ = true;
    } else if (is_origin(entry)) {
      if (std::find(origins_.begin(), origins_.end(), entry) == origins_.end()) origins_.push_back(entry);
    } else {
      throw std::invalid_argument("'" + entry + "' is not an origin (scheme://host[:port], or * for any)");
    }
  }
}

bool CorsPolicy::allows(std::string_view origin) const {
  if (origin.empty()) return false;
  auto o = normalize(origin);
  if (o == "null" || !is_origin(o)) return false;
  return any_ || std::find(origins_.begin(), origins_.end(), o) != origins_.end();
}

}  // namespace tourmap::server
