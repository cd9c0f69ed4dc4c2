#include "http.hpp"

namespace tourmap::api {

Response json_response(const nlohmann::json& body, int status) {
  Response r;
  r.status = status;
  // Replace invalid UTF-8 instead of throwing: a bad byte in imported data must not become a 500.
  r.body = body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  return r;
}

Response geojson_response(const nlohmann::json& body) {
  Response r = json_response(body);
  r.content_type = "application/geo+json";
  return r;
}

Response error_response(int status, const std::string& code, const std::string& message, const std::string& field) {
  nlohmann::json err = {{"code", code}, {"message", message}};
  err["field"] = field.empty() ? nlohmann::json(nullptr) : nlohmann::json(field);
  return json_response({{"error", err}}, status);
}

}  // namespace tourmap::api
