#include "geo/projection.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tourmap::geo {
namespace {

TEST(Projection, OriginMapsToZero) {
  LocalProjection proj{{16.37, 48.21}};
  auto xy = project(proj, {16.37, 48.21});
  EXPECT_NEAR(xy.x, 0.0, 1e-6);
  EXPECT_NEAR(xy.y, 0.0, 1e-6);
}

TEST(Projection, RoundTripsWithinAMillimetre) {
  LocalProjection proj{{-0.12, 51.5}};
  for (LonLat p : {LonLat{-0.5, 51.3}, LonLat{0.3, 51.7}, LonLat{-0.12, 51.5001}}) {
    auto back = unproject(proj, project(proj, p));
    EXPECT_NEAR(back.lon, p.lon, 1e-8);
    EXPECT_NEAR(back.lat, p.lat, 1e-8);
  }
}

TEST(Projection, DistancesAreMetresNearTheCentre) {
  LocalProjection proj{{16.37, 48.21}};
  LonLat a{16.36, 48.20}, b{16.38, 48.22};
  auto pa = project(proj, a), pb = project(proj, b);
  double planar = std::hypot(pa.x - pb.x, pa.y - pb.y);
  double geodesic = geodesic_distance_m(a, b);
  EXPECT_NEAR(planar, geodesic, geodesic * 1e-4);  // 0.01% over a city
  EXPECT_NEAR(geodesic, 2674.0, 5.0);              // about 2.7 km diagonal in Vienna
}

TEST(Projection, ProjectionForBoxIsCentred) {
  BBox box;
  box.extend({10.0, 50.0});
  box.extend({12.0, 52.0});
  auto proj = projection_for(box);
  EXPECT_DOUBLE_EQ(proj.origin.lon, 11.0);
  EXPECT_DOUBLE_EQ(proj.origin.lat, 51.0);
  EXPECT_NE(describe(proj).find("lon0=11.0000000"), std::string::npos);
}

TEST(BBox, EmptyUntilExtended) {
  BBox box;
  EXPECT_TRUE(box.empty());
  box.extend({1, 2});
  EXPECT_FALSE(box.empty());
  EXPECT_TRUE(box.contains({1, 2}));
  EXPECT_FALSE(box.contains({1.1, 2}));
}

TEST(LonLat, ValidityRejectsOutOfRangeAndNaN) {
  EXPECT_TRUE(is_valid({180, -90}));
  EXPECT_FALSE(is_valid({180.1, 0}));
  EXPECT_FALSE(is_valid({0, std::nan("")}));
  EXPECT_FALSE(is_valid({INFINITY, 0}));
}

}  // namespace
}  // namespace tourmap::geo
