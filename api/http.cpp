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

nlohmann::json error_object(const std::string& code, const std::string& message, const std::string& field) {
  return nlohmann::json::object({{"code", code},
                                 {"message", message},
                                 {"field", field.empty() ? nlohmann::json(nullptr) : nlohmann::json(field)}});
}

Response error_response(int status, const std::string& code, const std::string& message, const std::string& field) {
  return json_response(nlohmann::json::object({{"error", error_object(code, message, field)}}), status);
}

std::string ws_error_message(const std::string& code, const std::string& message, const std::string& field) {
  // Replacement, not an exception, for bytes that are not UTF-8 (a client's input echoed).
  return nlohmann::json::object({{"type", "error"}, {"error", error_object(code, message, field)}})
      .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace tourmap::api
