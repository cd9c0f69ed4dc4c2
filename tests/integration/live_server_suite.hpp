#pragma once
// A test suite that shares one live server between its tests: started before the first test,
// stopped after the last. A suite that needs server flags declares
//   static std::vector<std::string> server_flags() { return {...}; }
// in its public part. Also the checks every API suite makes of an error answer.

#include "live_server.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tourmap::test {

template <class Suite>
class LiveServerSuite : public ::testing::Test {
 protected:
  static std::vector<std::string> server_flags() { return {}; }
  static void SetUpTestSuite() { live = new LiveServer(Suite::server_flags()); }
  static void TearDownTestSuite() {
    delete live;
    live = nullptr;
  }
  static inline LiveServer* live = nullptr;
};

// An error answer as the API conventions give it: the status, a code and a message, and the
// field at fault (empty: no field names one, as for a body too large to read).
inline void expect_error(const HttpResult& r, int status, const std::string& field) {
  EXPECT_EQ(r.status, status) << r.body;
  if (r.status < 400) return;
  auto err = error_of(r);
  EXPECT_FALSE(err["code"].get<std::string>().empty()) << r.body;
  EXPECT_FALSE(err["message"].get<std::string>().empty()) << r.body;
  if (field.empty())
    EXPECT_TRUE(err["field"].is_null()) << r.body;
  else
    EXPECT_EQ(err["field"], field) << r.body;
}

}  // namespace tourmap::test
