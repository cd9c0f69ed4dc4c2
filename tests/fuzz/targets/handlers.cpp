// The whole request path of the HTTP server without a socket, as HttpSession::handle runs it:
// server::parse_target on the request target, the server's full route table
// (server::register_routes: every API handler plus /metrics and the spec) matched by
// api::Router, the handler run, then server::finish_response (ETag/304, gzip, HEAD); requests
// no route takes go to the static files (path traversal must not leave the web root). Write
// routes (Access::api_key) are refused as for a client without a key.
//
// Behind the handlers: support/server_world.hpp.
//
// Input: "METHOD TARGET\n", then header lines ("Content-Type: ...", "Accept: ...",
// "Accept-Encoding: ...", "If-None-Match: ..."), an empty line, and the body.
// Clean outcome: any response. A handler exception other than api::ApiError (a 500 in the
// server) is a finding: it escapes the harness.

#include "fuzz_common.hpp"
#include "support/server_world.hpp"

#include "server/respond.hpp"
#include "server/url.hpp"

#include <boost/beast/core/string.hpp>

#include <memory>

namespace {

using namespace tourmap;

using fuzz::kSecret;

fuzz::ServerWorld& world() {
  static fuzz::ServerWorld w;
  return w;
}

api::Response run(const api::Route& route, api::Request& req) {
  try {
    return route.handler(req);
  } catch (const api::ApiError& e) {
    FUZZ_CHECK(e.status >= 400 && e.status <= 599);
    return api::error_response(e);
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  world();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::ServerWorld& w = world();
  std::string_view in = fuzz::as_view(data, size);
  auto eol = in.find('\n');
  std::string_view line = in.substr(0, eol);
  in = eol == std::string_view::npos ? std::string_view() : in.substr(eol + 1);
  auto space = line.find(' ');
  if (space == std::string_view::npos) return 0;
  std::string method(line.substr(0, space));
  std::string_view raw_target = line.substr(space + 1);

  server::RequestFacts facts;
  facts.method = server::http::string_to_verb(method);
  if (facts.method == server::http::verb::unknown) return 0;  // Beast refuses these before us
  std::string content_type, accept;
  while (!in.empty()) {
    eol = in.find('\n');
    std::string_view h = in.substr(0, eol);
    in = eol == std::string_view::npos ? std::string_view() : in.substr(eol + 1);
    if (h.empty()) break;
    auto colon = h.find(':');
    if (colon == std::string_view::npos) continue;
    auto name = h.substr(0, colon);
    auto value = h.substr(colon + 1);
    while (!value.empty() && value.front() == ' ') value.remove_prefix(1);
    if (boost::beast::iequals(name, "content-type")) content_type = value;
    else if (boost::beast::iequals(name, "accept")) accept = value;
    else if (boost::beast::iequals(name, "accept-encoding")) facts.accept_encoding = value;
    else if (boost::beast::iequals(name, "if-none-match")) facts.if_none_match = value;
  }

  auto target = server::parse_target(raw_target);
  if (!target) return 0;  // 400 invalid_target
  api::Request req;
  req.method = method;
  req.path = std::move(target->path);
  req.query = std::move(target->query);
  req.body.assign(in);
  req.content_type = content_type;
  req.accept = accept;

  api::Response r;
  auto match = w.state.router.match(req);
  if (match.route && match.route->access == api::Access::api_key) {
    // Writes need an API key, checked by the server before the body is read; an anonymous
    // client gets 401. Their bodies go to the loaders, which the import targets fuzz.
    r = api::error_response(401, "unauthorized", "this request needs an API key", "X-API-Key");
  } else if (match.route) {
    r = run(*match.route, req);
  } else if (!match.allowed.empty()) {
    r = api::error_response(405, "method_not_allowed", req.method + " is not allowed here", "method");
  } else {
    bool api_path = req.path.rfind("/api/", 0) == 0 || req.path == "/healthz" || req.path == "/metrics";
    std::optional<api::Response> file;
    if (!api_path && (facts.method == server::http::verb::get || facts.method == server::http::verb::head))
      file = w.state.static_files.serve(req.path);
    FUZZ_CHECK(!file || file->body.find(kSecret) == std::string::npos);  // never leaves the web root
    r = file ? std::move(*file) : api::error_response(404, "not_found", "nothing at " + req.path, "path");
  }
  auto res = server::finish_response(std::move(r), facts, w.config);
  (void)res;
  return 0;
}
