#pragma once
// Camera matrices (OpenGL conventions: right-handed eye space looking down -z, clip z in [-w, w])
// and the crowd::CameraView that the LOD cut and the renderer take.

#include "crowd/lod_cut.hpp"

#include <Eigen/Core>

namespace tourmap::render {

// World -> eye. Throws std::invalid_argument when eye == target or `up` is parallel to the view.
Eigen::Matrix4f look_at(const Eigen::Vector3f& eye, const Eigen::Vector3f& target, const Eigen::Vector3f& up);

// Eye -> clip. Throws std::invalid_argument unless 0 < fov_y < pi, aspect > 0, 0 < near < far.
Eigen::Matrix4f perspective(float fov_y_rad, float aspect, float near_m, float far_m);

// A complete view for an output of width x height pixels (1..1920 x 1..1080 for the renderer).
crowd::CameraView make_camera_view(const Eigen::Vector3f& eye, const Eigen::Vector3f& target,
                                   const Eigen::Vector3f& up, float fov_y_rad, int width, int height,
                                   float near_m = 0.1f, float far_m = 1000.f);

// The unit viewing direction of a view (from the w row of view_proj).
Eigen::Vector3f view_direction(const crowd::CameraView& view);

}  // namespace tourmap::render
