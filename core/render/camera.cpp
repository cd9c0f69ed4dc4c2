#include "camera.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace tourmap::render {

Eigen::Matrix4f look_at(const Eigen::Vector3f& eye, const Eigen::Vector3f& target, const Eigen::Vector3f& up) {
  const Eigen::Vector3f forward = target - eye;
  if (!forward.allFinite() || forward.norm() < 1e-6f) throw std::invalid_argument("look_at: eye and target coincide");
  const Eigen::Vector3f f = forward.normalized();
  const Eigen::Vector3f side = f.cross(up);
  if (!side.allFinite() || side.norm() < 1e-6f * std::max(1.f, up.norm()))
    throw std::invalid_argument("look_at: up vector is zero or parallel to the viewing direction");
  const Eigen::Vector3f s = side.normalized();
  const Eigen::Vector3f u = s.cross(f);
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m;
}

Eigen::Matrix4f perspective(float fov_y_rad, float aspect, float near_m, float far_m) {
  if (!(fov_y_rad > 0 && fov_y_rad < std::numbers::pi_v<float>))
    throw std::invalid_argument("perspective: fov_y must be in (0, pi) radians, got " + std::to_string(fov_y_rad));
  if (!(aspect > 0) || !std::isfinite(aspect)) throw std::invalid_argument("perspective: aspect must be positive");
  if (!(near_m > 0 && far_m > near_m) || !std::isfinite(far_m))
    throw std::invalid_argument("perspective: need 0 < near < far, got near " + std::to_string(near_m) + " far " +
                                std::to_string(far_m));
  const float t = 1.f / std::tan(fov_y_rad * 0.5f);
  Eigen::Matrix4f m = Eigen::Matrix4f::Zero();
  m(0, 0) = t / aspect;
  m(1, 1) = t;
  m(2, 2) = (far_m + near_m) / (near_m - far_m);
  m(2, 3) = 2.f * far_m * near_m / (near_m - far_m);
  m(3, 2) = -1.f;
  return m;
}

crowd::CameraView make_camera_view(const Eigen::Vector3f& eye, const Eigen::Vector3f& target,
                                   const Eigen::Vector3f& up, float fov_y_rad, int width, int height,
                                   float near_m, float far_m) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("make_camera_view: size must be positive, got " + std::to_string(width) + "x" +
                                std::to_string(height));
  crowd::CameraView view;
  view.view_proj = perspective(fov_y_rad, static_cast<float>(width) / static_cast<float>(height), near_m, far_m) *
                   look_at(eye, target, up);
  view.eye = eye;
  view.width = width;
  view.height = height;
  view.fov_y_rad = fov_y_rad;
  view.near_m = near_m;
  view.far_m = far_m;
  return view;
}

Eigen::Vector3f view_direction(const crowd::CameraView& view) {
  // Row 3 of P*V is -(row 2 of V) = the forward axis (P's w row is (0, 0, -1, 0)).
  const Eigen::Vector3f w = view.view_proj.block<1, 3>(3, 0).transpose();
  return w.norm() > 0 ? w.normalized() : Eigen::Vector3f(0, 0, -1);
}

}  // namespace tourmap::render
