#pragma once
// Routes: method + path pattern with {name} segments, e.g. /api/v1/cities/{id}/metro.
// Each route says where it runs, and who may call it: anyone (reads) or holders of an API key
// (writes). Where it runs:
//   io    - on the IO thread (microseconds: health, the API index)
//   light - on the read pool: cheap, bounded reads (catalog, metro, POIs, roads), which must
//           never wait behind expensive work
//   heavy - on the compute pool: layouts, deformations, rasters, clusters, imports; at most a
//           few per client address at once, each with a deadline and stopped when its client
//           goes away

#include "http.hpp"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace tourmap::api {

enum class Exec { io, light, heavy };
enum class Access { open, api_key };  // api_key: checked by the server before the body is read

using Handler = std::function<Response(Request&)>;

struct Route {
  std::string method;
  std::string pattern;  // also the metrics label
  Exec exec = Exec::heavy;
  Handler handler;
  std::vector<std::string> segments;  // pattern split at '/'; "{x}" marks a parameter
  Access access = Access::open;
};

struct RouteMatch {
  const Route* route = nullptr;            // null: no route for this method and path
  std::vector<std::string> allowed;        // methods the path has, when the method did not match
};

class Router {
 public:
  void add(std::string method, std::string pattern, Exec exec, Handler handler);
  // A write: only requests with a valid API key reach the handler.
  void add_write(std::string method, std::string pattern, Exec exec, Handler handler);
  // Finds the route and fills `request.params`.
  RouteMatch match(Request& request) const;
  const std::vector<Route>& routes() const { return routes_; }

 private:
  std::vector<Route> routes_;
};

std::vector<std::string> split_path(const std::string& path);

}  // namespace tourmap::api
