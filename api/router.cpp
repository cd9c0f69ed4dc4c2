#include "router.hpp"

#include <algorithm>

namespace tourmap::api {

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= path.size()) {
    auto slash = path.find('/', start);
    if (slash == std::string::npos) slash = path.size();
    if (slash > start) out.push_back(path.substr(start, slash - start));
    start = slash + 1;
  }
  return out;
}

void Router::add(std::string method, std::string pattern, Exec exec, Handler handler) {
  Route r;
  r.method = std::move(method);
  r.pattern = std::move(pattern);
  r.exec = exec;
  r.handler = std::move(handler);
  r.segments = split_path(r.pattern);
  routes_.push_back(std::move(r));
}

void Router::add_write(std::string method, std::string pattern, Exec exec, Handler handler) {
  add(std::move(method), std::move(pattern), exec, std::move(handler));
  routes_.back().access = Access::api_key;
}

namespace {

bool is_param(const std::string& segment) {
  return segment.size() > 2 && segment.front() == '{' && segment.back() == '}';
}

bool matches(const Route& route, const std::vector<std::string>& parts, std::map<std::string, std::string>* params) {
  if (route.segments.size() != parts.size()) return false;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const auto& seg = route.segments[i];
    if (is_param(seg)) {
      if (params) (*params)[seg.substr(1, seg.size() - 2)] = parts[i];
    } else if (seg != parts[i]) {
      return false;
    }
  }
  return true;
}

}  // namespace

RouteMatch Router::match(Request& request) const {
  auto parts = split_path(request.path);
  RouteMatch result;
  // HEAD is served by the GET route (the server drops the body).
  const std::string& method = request.method == "HEAD" ? std::string("GET") : request.method;
  for (const auto& route : routes_) {
    if (!matches(route, parts, nullptr)) continue;
    if (route.method == method) {
      request.params.clear();
      matches(route, parts, &request.params);
      result.route = &route;
      return result;
    }
    if (std::find(result.allowed.begin(), result.allowed.end(), route.method) == result.allowed.end())
      result.allowed.push_back(route.method);
  }
  return result;
}

}  // namespace tourmap::api
