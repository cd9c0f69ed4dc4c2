// The crowd stream's view messages (api/crowd_view: apply_view_message), parsed as the stream
// parses them (nlohmann::json::parse without exceptions; discarded documents are refused
// before validation). Every line of the input is one message applied on top of the view the
// previous ones left, as a connection does. Clean error: api::ApiError (the stream answers
// with an error message and keeps the previous view).

#include "fuzz_common.hpp"

#include "api/crowd_view.hpp"

#include <cmath>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tourmap;
  const api::CrowdLimits limits;
  api::CrowdView view;
  for (auto text : fuzz::split(fuzz::as_view(data, size), "\n", 64)) {
    const auto msg = nlohmann::json::parse(text, nullptr, false);
    if (msg.is_discarded()) continue;
    try {
      view = api::apply_view_message(msg, view, limits);
    } catch (const api::ApiError& e) {
      FUZZ_CHECK(e.status == 400);
      continue;
    }
    // What the renderer relies on after a successful message.
    FUZZ_CHECK(!view.scene.empty());
    FUZZ_CHECK(view.width >= limits.min_width && view.width <= limits.max_width);
    FUZZ_CHECK(view.height >= limits.min_height && view.height <= limits.max_height);
    FUZZ_CHECK(std::isfinite(view.poe) && std::isfinite(view.fov));
  }
  return 0;
}
