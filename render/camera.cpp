#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace bsg::render {
namespace {

using envs::Vec3;

constexpr double kDegree = std::numbers::pi / 180;

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 normalized(const Vec3& a) {
  const double length = std::sqrt(dot(a, a));
  return {a[0] / length, a[1] / length, a[2] / length};
}

// PyBullet (upAxis z) rotates by Rz(yaw)·Rx(pitch) (setEulerZYX(yaw, roll = 0, pitch)).
Vec3 rotate_yaw_pitch(const Vec3& v, double yaw, double pitch) {
  const Vec3 rx{v[0], std::cos(pitch) * v[1] - std::sin(pitch) * v[2],
                std::sin(pitch) * v[1] + std::cos(pitch) * v[2]};
  return {std::cos(yaw) * rx[0] - std::sin(yaw) * rx[1],
          std::sin(yaw) * rx[0] + std::cos(yaw) * rx[1], rx[2]};
}

Vec3 up_vector(const Camera& camera) {
  return rotate_yaw_pitch({0, 0, 1}, camera.yaw_deg * kDegree, camera.pitch_deg * kDegree);
}

// Half the side of the square each world's walls enclose, with the walls.
double arena_half_extent(const envs::SceneView& scene) {
  return scene.task == "Circle" ? 12.2 : 10.1;
}

}  // namespace

std::vector<std::string> camera_names() { return {"default", "arena", "track", "top"}; }

Camera camera_for(const envs::SceneView& scene, std::string_view name, double aspect) {
  Camera camera;
  const Vec3& agent = scene.agent_position;
  if (name == "default") {
    if (scene.task == "Run") {
      camera.target = {agent[0] + 3, 0, 2};
      camera.distance_m = 2.5;
      camera.yaw_deg = 90;
      camera.pitch_deg = -50;
    } else {
      camera.target = {0, -3, 0};
      camera.distance_m = 1.2 * scene.env_dim;
      camera.yaw_deg = 0;
      camera.pitch_deg = -60;
    }
    return camera;
  }
  if (name == "arena") {
    if (scene.task == "Run") {
      // The stretch of lane around the agent, widened where it left the lane.
      const double y0 = std::min(-3.0, agent[1] - 1.5), y1 = std::max(3.0, agent[1] + 1.5);
      return oblique_camera_over({agent[0] - 6, y0, 0}, {agent[0] + 10, y1, 2}, 0, -50, aspect);
    }
    const double h = arena_half_extent(scene);
    return oblique_camera_over({-h, -h, 0}, {h, h, 2}, 0, -60, aspect);
  }
  if (name == "track") {
    camera.target = agent;
    camera.distance_m = 4;
    camera.yaw_deg = 0;
    camera.pitch_deg = -35;
    return camera;
  }
  if (name == "top") {
    if (scene.task == "Run") return top_camera_over(agent[0] - 8, agent[0] + 8, -4, 4, aspect);
    const double h = arena_half_extent(scene);
    return top_camera_over(-h, h, -h, h, aspect);
  }
  require_camera_name(std::string(name));
  throw std::logic_error("camera_for: camera '" + std::string(name) + "' has no definition");
}

void require_camera_name(const std::string& name) {
  const std::vector<std::string> names = camera_names();
  if (std::find(names.begin(), names.end(), name) != names.end()) return;
  std::string valid;
  for (const std::string& n : names) valid += (valid.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown camera '" + name + "' (valid: " + valid + ")");
}

Camera top_camera_over(double x0, double x1, double y0, double y1, double aspect) {
  Camera camera;
  camera.target = {(x0 + x1) / 2, (y0 + y1) / 2, 0};
  camera.yaw_deg = 0;
  camera.pitch_deg = -90;
  const double half_height = std::max((y1 - y0) / 2, (x1 - x0) / 2 / aspect) * 1.04;
  camera.distance_m = half_height / std::tan(camera.vertical_fov_deg * kDegree / 2);
  camera.far_m = camera.distance_m + 10;
  return camera;
}

Camera oblique_camera_over(const Vec3& low, const Vec3& high, double yaw_deg, double pitch_deg,
                          double aspect) {
  Camera camera;
  camera.target = {(low[0] + high[0]) / 2, (low[1] + high[1]) / 2, low[2]};
  camera.yaw_deg = yaw_deg;
  camera.pitch_deg = pitch_deg;
  const double diagonal = std::sqrt(dot(sub(high, low), sub(high, low)));
  // Steps of 1/200 of the diagonal out from half of it: the first distance at
  // which every corner is inside the frame, 4% in from its edges.
  for (int step = 100; step <= 2000; ++step) {
    camera.distance_m = diagonal * step / 200.0;
    camera.far_m = camera.distance_m + 2 * diagonal;
    const Mat4 clip = multiply(projection_matrix(camera, aspect), view_matrix(camera));
    bool inside = true;
    for (int corner = 0; corner < 8 && inside; ++corner) {
      const Vec3 p{(corner & 1) ? high[0] : low[0], (corner & 2) ? high[1] : low[1],
                   (corner & 4) ? high[2] : low[2]};
      double x = clip[12], y = clip[13], w = clip[15];
      for (int k = 0; k < 3; ++k) {
        x += clip[static_cast<size_t>(k * 4)] * p[static_cast<size_t>(k)];
        y += clip[static_cast<size_t>(k * 4 + 1)] * p[static_cast<size_t>(k)];
        w += clip[static_cast<size_t>(k * 4 + 3)] * p[static_cast<size_t>(k)];
      }
      inside = w > camera.near_m && std::abs(x) <= 0.92 * w && std::abs(y) <= 0.92 * w;
    }
    if (inside) return camera;
  }
  return camera;  // 10 diagonals away: everything a box can hold is in view long before
}

Vec3 eye_position(const Camera& camera) {
  // PyBullet puts the eye at −distance along the forward axis (y for upAxis z),
  // rotates it, then moves it to the target.
  const Vec3 offset = rotate_yaw_pitch({0, -camera.distance_m, 0}, camera.yaw_deg * kDegree,
                                       camera.pitch_deg * kDegree);
  return {camera.target[0] + offset[0], camera.target[1] + offset[1],
          camera.target[2] + offset[2]};
}

Mat4 view_matrix(const Camera& camera) {
  // gluLookAt, as PyBullet's computeViewMatrixFromPositions.
  const Vec3 eye = eye_position(camera);
  const Vec3 forward = normalized(sub(camera.target, eye));
  const Vec3 side = normalized(cross(forward, up_vector(camera)));
  const Vec3 up = cross(side, forward);
  Mat4 m{};
  for (int c = 0; c < 3; ++c) {
    m[c * 4 + 0] = side[static_cast<size_t>(c)];
    m[c * 4 + 1] = up[static_cast<size_t>(c)];
    m[c * 4 + 2] = -forward[static_cast<size_t>(c)];
  }
  m[12] = -dot(side, eye);
  m[13] = -dot(up, eye);
  m[14] = dot(forward, eye);
  m[15] = 1;
  return m;
}

Mat4 projection_matrix(const Camera& camera, double aspect) {
  const double y_scale = 1 / std::tan(camera.vertical_fov_deg * kDegree / 2);
  const double n = camera.near_m, f = camera.far_m;
  Mat4 m{};
  m[0] = y_scale / aspect;
  m[5] = y_scale;
  m[10] = (f + n) / (n - f);
  m[11] = -1;
  m[14] = 2 * f * n / (n - f);
  return m;
}

Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 m{};
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      double sum = 0;
      for (int k = 0; k < 4; ++k) sum += a[static_cast<size_t>(k * 4 + r)] * b[static_cast<size_t>(c * 4 + k)];
      m[static_cast<size_t>(c * 4 + r)] = sum;
    }
  }
  return m;
}

}  // namespace bsg::render
