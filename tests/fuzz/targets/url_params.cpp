// Request targets and query parameters: server::parse_target (percent-decoding of the path and
// the query, as HttpSession does for every request), then every query-string reader the
// handlers use on the decoded parameters (api/params: query_bbox, query_int, query_bool,
// require_slug; api/metro_layout: parse_layout_query). Clean error: api::ApiError.

#include "fuzz_common.hpp"

#include "api/metro_layout.hpp"
#include "api/params.hpp"
#include "server/url.hpp"

#include <cstring>

namespace {

template <class F>
void clean(F&& f) {
  try {
    f();
  } catch (const tourmap::api::ApiError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tourmap;
  const std::string_view text = fuzz::as_view(data, size);
  (void)server::percent_decode(text, true);
  auto decoded = server::percent_decode(text, false);
  FUZZ_CHECK(!decoded || !std::memchr(decoded->data(), '\0', decoded->size()));  // promised: no NUL

  auto target = server::parse_target(text);
  if (!target) return 0;
  FUZZ_CHECK(!target->path.empty() && target->path[0] == '/');
  api::Request req;
  req.method = "GET";
  req.path = target->path;
  req.query = std::move(target->query);

  clean([&] { (void)api::query_bbox(req); });
  clean([&] { (void)api::query_bbox(req, "within"); });
  for (const char* name : {"limit", "offset", "width", "height", "m", "count"})
    clean([&] { (void)api::query_int(req, name, 1, 10000, 100); });
  clean([&] { (void)api::query_int(req, "offset", 0, 1LL << 40, 0); });
  for (const char* name : {"geometry", "skip_outside", "all"}) clean([&] { (void)api::query_bool(req, name, false); });
  clean([&] { (void)api::parse_layout_query(req).canonical(); });
  // Path segments as ids (the handlers' require_slug on {id}).
  std::size_t start = 1;
  while (start <= req.path.size()) {
    auto slash = req.path.find('/', start);
    auto seg = req.path.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
    clean([&] { api::require_slug(seg, "city"); });
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return 0;
}
