// Cameras of the renderer: PyBullet's yaw/pitch/distance orbit camera around a
// target, z up, roll 0 (computeViewMatrixFromYawPitchRoll with upAxis z), and
// a perspective projection (computeProjectionMatrixFOV), as column-major 4×4
// matrices in OpenGL's clip-space convention.
//
// Named cameras (camera_for):
//   default  the original's per task: Circle, Gather, Reach target (0, −3, 0),
//            distance 1.2·env_dim, yaw 0, pitch −60; Run target
//            (x_agent + 3, 0, 2), distance 2.5, yaw 90, pitch −50
//   arena    the whole arena at the original's angle, so the agent is in view
//            wherever it goes: Circle, Gather, Reach the walled square up to 2 m
//            high, yaw 0, pitch −60; Run 16 m of lane around the agent
//            (x_agent − 6 to x_agent + 10, y from −3 to 3, widened to keep the
//            agent 1.5 m inside), yaw 0, pitch −50; the distance is the
//            nearest at which the box's corners are 4% inside the frame
//   track    follows the agent: target its base, distance 4, yaw 0, pitch −35
//   top      straight down over the whole arena (Run: over the agent's stretch of lane)
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "envs/assembly/scene.h"

namespace bsg::render {

using Mat4 = std::array<double, 16>;  // column-major: element (row r, column c) at [c·4 + r]

struct Camera {
  envs::Vec3 target{};
  double distance_m = 10;
  double yaw_deg = 0;
  double pitch_deg = -60;
  double vertical_fov_deg = 60;
  double near_m = 0.1;
  double far_m = 100;
};

// The camera names camera_for accepts, in the order documented above.
std::vector<std::string> camera_names();

// Throws std::invalid_argument unless `name` is one of camera_names(), naming
// it and listing the valid names.
void require_camera_name(const std::string& name);

// The named camera for this scene and image aspect (width / height); throws
// std::invalid_argument naming the camera and listing the valid names.
Camera camera_for(const envs::SceneView& scene, std::string_view name, double aspect);

// A camera looking straight down at the rectangle [x0, x1] × [y0, y1] so that it fills the
// image of the given aspect (width / height) with a small margin.
Camera top_camera_over(double x0, double x1, double y0, double y1, double aspect);

// A camera at this yaw and pitch aimed at the centre of the box's floor, at the
// nearest distance (in steps of 1/200 of the box's diagonal) from which all
// eight corners of the box low–high are 4% or more inside the image's edges.
Camera oblique_camera_over(const envs::Vec3& low, const envs::Vec3& high, double yaw_deg, double pitch_deg,
                          double aspect);

// Where the camera's eye is, as PyBullet places it.
envs::Vec3 eye_position(const Camera& camera);
Mat4 view_matrix(const Camera& camera);
Mat4 projection_matrix(const Camera& camera, double aspect);
Mat4 multiply(const Mat4& a, const Mat4& b);

}  // namespace bsg::render
