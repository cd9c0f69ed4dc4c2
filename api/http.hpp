#pragma once
// Transport-neutral request/response types: handlers see these, never Beast. That keeps the
// handlers testable and fuzzable without a socket.

#include <nlohmann/json.hpp>

#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace tourmap::api {

struct Request {
  std::string method;  // "GET", "POST", ...
  std::string path;    // percent-decoded path, no query
  std::map<std::string, std::string> query;   // decoded query parameters (last one wins)
  std::map<std::string, std::string> params;  // path parameters from the route pattern
  std::string body;
  std::string content_type;
  std::string accept;  // the Accept header ("" when absent)

  // Query parameter or nullptr.
  const std::string* query_param(const std::string& name) const {
    auto it = query.find(name);
    return it == query.end() ? nullptr : &it->second;
  }
  const std::string& param(const std::string& name) const { return params.at(name); }
};

struct Response {
  int status = 200;
  std::string content_type = "application/json";
  std::string body;
  bool cacheable = false;  // a GET result clients may revalidate with ETag
  int max_age_s = 0;       // Cache-Control max-age for cacheable responses
  std::vector<std::pair<std::string, std::string>> headers;
};

// A client error (4xx) or a refusal (503) with the field it is about. Handlers throw it;
// the server turns it into {"error": {"code", "message", "field"}}. `message` is the whole
// text (what() stops at a NUL byte a client may have sent).
class ApiError : public std::runtime_error {
 public:
  ApiError(int status, std::string code, std::string message, std::string field = "")
      : std::runtime_error(message), status(status), code(std::move(code)), message(std::move(message)),
        field(std::move(field)) {}
  int status;
  std::string code;
  std::string message;
  std::string field;
};

Response json_response(const nlohmann::json& body, int status = 200);
Response geojson_response(const nlohmann::json& body);

// The one error shape of every answer, HTTP and WebSocket alike:
//   {"code": "...", "message": "...", "field": "..." or null}
nlohmann::json error_object(const std::string& code, const std::string& message, const std::string& field = "");
// HTTP: status + {"error": error_object}.
Response error_response(int status, const std::string& code, const std::string& message,
                        const std::string& field = "");
inline Response error_response(const ApiError& e) { return error_response(e.status, e.code, e.message, e.field); }
// WebSocket text message: {"type": "error", "error": error_object}.
std::string ws_error_message(const std::string& code, const std::string& message, const std::string& field = "");
inline std::string ws_error_message(const ApiError& e) { return ws_error_message(e.code, e.message, e.field); }

}  // namespace tourmap::api
