#include "render/camera.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace tourmap::render {
namespace {

TEST(Camera, LookAtPutsTheTargetOnTheNegativeZAxis) {
  const Eigen::Vector3f eye(3, 2, 5), target(-1, 0.5f, -2);
  const Eigen::Matrix4f v = look_at(eye, target, Eigen::Vector3f::UnitY());
  const Eigen::Vector4f t = v * target.homogeneous();
  EXPECT_NEAR(t.x(), 0, 1e-5);
  EXPECT_NEAR(t.y(), 0, 1e-5);
  EXPECT_NEAR(t.z(), -(target - eye).norm(), 1e-4);
  const Eigen::Vector4f e = v * eye.homogeneous();
  EXPECT_NEAR(e.head<3>().norm(), 0, 1e-5);
  // World up stays up on screen.
  const Eigen::Vector4f above = v * (target + Eigen::Vector3f::UnitY()).homogeneous();
  EXPECT_GT(above.y(), 0.5f);
}

TEST(Camera, PerspectiveMapsNearAndFarToMinusOneAndOne) {
  const Eigen::Matrix4f p = perspective(1.0f, 1.5f, 0.5f, 100.f);
  Eigen::Vector4f n = p * Eigen::Vector4f(0, 0, -0.5f, 1);
  Eigen::Vector4f f = p * Eigen::Vector4f(0, 0, -100.f, 1);
  EXPECT_NEAR(n.z() / n.w(), -1, 1e-5);
  EXPECT_NEAR(f.z() / f.w(), 1, 1e-4);
  // A point on the top edge of the view at depth 2.
  const float top = 2.f * std::tan(0.5f);
  Eigen::Vector4f e = p * Eigen::Vector4f(0, top, -2, 1);
  EXPECT_NEAR(e.y() / e.w(), 1, 1e-5);
}

TEST(Camera, ViewDirectionAndBadInput) {
  const crowd::CameraView v = make_camera_view({0, 1, 5}, {0, 1, 0}, {0, 1, 0}, 1.0f, 160, 120);
  EXPECT_TRUE(view_direction(v).isApprox(Eigen::Vector3f(0, 0, -1), 1e-5f));
  EXPECT_EQ(v.width, 160);
  EXPECT_THROW(look_at({1, 1, 1}, {1, 1, 1}, {0, 1, 0}), std::invalid_argument);
  EXPECT_THROW(look_at({0, 0, 0}, {0, 5, 0}, {0, 1, 0}), std::invalid_argument);
  EXPECT_THROW(perspective(0.f, 1.f, 0.1f, 10.f), std::invalid_argument);
  EXPECT_THROW(perspective(1.f, 1.f, 0.f, 10.f), std::invalid_argument);
  EXPECT_THROW(perspective(1.f, 1.f, 1.f, 1.f), std::invalid_argument);
  EXPECT_THROW(make_camera_view({0, 1, 5}, {0, 1, 0}, {0, 1, 0}, 1.0f, 0, 120), std::invalid_argument);
}

}  // namespace
}  // namespace tourmap::render
