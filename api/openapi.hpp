#pragma once
// The API contract (api/openapi.yaml), embedded at build time and served at /api/v1/openapi.yaml.

#include <string_view>

namespace tourmap::api {

std::string_view openapi_yaml();

}  // namespace tourmap::api
