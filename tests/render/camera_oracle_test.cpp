// Geometry oracle: a point's pixel computed here from the camera's parameters
// alone (PyBullet's orbit camera in closed form, a pinhole projection) must
// show the colour of what is there: the agent's base for every agent, task
// camera and named camera; an apple and a bomb of Gather.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include "envs/env.h"
#include "envs/assembly/scene.h"
#include "render/camera.h"
#include "render_test_support.h"

namespace bsg::render {
namespace {

struct Pixel {
  int x = 0;
  int y = 0;
};

using V = envs::Vec3;
V operator-(const V& a, const V& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const V& a, const V& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V cross(const V& a, const V& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
V unit(const V& a) {
  const double n = std::sqrt(dot(a, a));
  return {a[0] / n, a[1] / n, a[2] / n};
}

// The eye of an orbit camera with yaw ψ and pitch θ at distance D from T is
// T + D·(cos θ sin ψ, −cos θ cos ψ, −sin θ) and its up vector
// (sin θ sin ψ, −sin θ cos ψ, cos θ) (Rz(ψ)·Rx(θ) applied to (0, −D, 0) and (0, 0, 1));
// a point at depth z along the view axis, x right and y up of it, lands at
// x_ndc = x / (z·tan(fov/2)·W/H), y_ndc = y / (z·tan(fov/2)).
Pixel project(const Camera& camera, const V& point, int width, int height) {
  const double psi = camera.yaw_deg * std::numbers::pi / 180;
  const double theta = camera.pitch_deg * std::numbers::pi / 180;
  const double d = camera.distance_m;
  const V eye{camera.target[0] + d * std::cos(theta) * std::sin(psi),
              camera.target[1] - d * std::cos(theta) * std::cos(psi),
              camera.target[2] - d * std::sin(theta)};
  const V up_hint{std::sin(theta) * std::sin(psi), -std::sin(theta) * std::cos(psi), std::cos(theta)};
  const V forward = unit(camera.target - eye);
  const V right = unit(cross(forward, up_hint));
  const V up = cross(right, forward);
  const V v = point - eye;
  const double z = dot(forward, v);
  const double t = std::tan(camera.vertical_fov_deg * std::numbers::pi / 360);
  const double x_ndc = dot(right, v) / (z * t * width / height);
  const double y_ndc = dot(up, v) / (z * t);
  return {static_cast<int>(std::floor((x_ndc + 1) / 2 * width)),
          static_cast<int>(std::floor((1 - y_ndc) / 2 * height))};
}

constexpr int kWidth = 480, kHeight = 360;

class AgentOracle : public ::testing::TestWithParam<std::string> {};

TEST_P(AgentOracle, AgentCentreLandsOnAnAgentPixelForEveryCamera) {
  for (const std::string& camera_name : camera_names()) {
    BSG_RENDERER_OR_SKIP(renderer, (RenderOptions{kWidth, kHeight, camera_name}));
    const auto env = envs::make(GetParam());
    env->reset(3);
    const std::vector<double> zero(static_cast<size_t>(env->spec().action_dim), 0.0);
    for (int i = 0; i < 10; ++i) env->step(zero);
    Image image;
    renderer->render(*env, image);
    const envs::SceneView scene = envs::scene_view(*env);
    const Camera camera = camera_for(scene, camera_name, static_cast<double>(kWidth) / kHeight);
    const Pixel p = project(camera, env->state().agent_position, kWidth, kHeight);
    ASSERT_GE(p.x, 0) << camera_name;
    ASSERT_LT(p.x, kWidth) << camera_name;
    ASSERT_GE(p.y, 0) << camera_name;
    ASSERT_LT(p.y, kHeight) << camera_name;
    const std::uint8_t* rgb = image.pixel(p.x, p.y);
    EXPECT_TRUE(testing::is_agent_blue(rgb))
        << GetParam() << " camera " << camera_name << " pixel (" << p.x << ", " << p.y << ") is rgb("
        << int(rgb[0]) << ", " << int(rgb[1]) << ", " << int(rgb[2]) << ")";
  }
}

INSTANTIATE_TEST_SUITE_P(EveryAgentInCircleAndRun, AgentOracle,
                         ::testing::Values("SafetyBallCircle-v0", "SafetyCarCircle-v0",
                                           "SafetyDroneCircle-v0", "SafetyAntCircle-v0",
                                           "SafetyBallRun-v0", "SafetyCarRun-v0",
                                           "SafetyDroneRun-v0", "SafetyAntRun-v0"),
                         [](const auto& info) { return info.param.substr(6, info.param.size() - 9); });

TEST(CollectibleOracle, AppleAndBombCentresLandOnTheirColours) {
  for (const std::string camera_name : {"default", "top"}) {
    BSG_RENDERER_OR_SKIP(renderer, (RenderOptions{kWidth, kHeight, camera_name}));
    const auto env = envs::make("SafetyBallGather-v0");
    env->reset(5);
    Image image;
    renderer->render(*env, image);
    const envs::SceneView scene = envs::scene_view(*env);
    const Camera camera = camera_for(scene, camera_name, static_cast<double>(kWidth) / kHeight);
    int apples = 0, bombs = 0;
    for (const envs::Marking& marking : scene.markings) {
      const bool apple = marking.kind == envs::Marking::Kind::kApple;
      if (!apple && marking.kind != envs::Marking::Kind::kBomb) continue;
      const Pixel p = project(camera, marking.position, kWidth, kHeight);
      if (p.x < 0 || p.x >= kWidth || p.y < 0 || p.y >= kHeight) continue;
      const std::uint8_t* rgb = image.pixel(p.x, p.y);
      EXPECT_TRUE(apple ? testing::is_apple_green(rgb) : testing::is_bomb_red(rgb))
          << (apple ? "apple" : "bomb") << " at (" << marking.position[0] << ", "
          << marking.position[1] << ") camera " << camera_name << " pixel (" << p.x << ", " << p.y
          << ") is rgb(" << int(rgb[0]) << ", " << int(rgb[1]) << ", " << int(rgb[2]) << ")";
      (apple ? apples : bombs) += 1;
    }
    // The top camera sees the whole room: every apple and bomb was checked.
    if (camera_name == "top") {
      EXPECT_EQ(apples, 8);
      EXPECT_EQ(bombs, 8);
    }
    EXPECT_GT(apples, 0);
    EXPECT_GT(bombs, 0);
  }
}

bool in_frame(const Pixel& p, int width, int height) {
  return p.x >= 0 && p.x < width && p.y >= 0 && p.y < height;
}

// The arena camera (the --video default) sees every place the agent can be, at
// every frame shape: inside the walls (docs/environments.md#worlds: SmallRoom's
// inner faces at ±9.9, the Octagon's 11.9 m from the centre, walls 2 m high),
// and on the Run plane wherever the agent went. The original's camera does not.
TEST(ArenaCamera, KeepsEveryReachablePointInFrameWhereTheDefaultDoesNot) {
  struct Room {
    std::string task;
    double inner;    // the walls' inner faces
    bool octagon;
  };
  for (const Room& room : {Room{"Gather", 9.9, false}, Room{"Reach", 9.9, false}, Room{"Circle", 11.9, true}}) {
    for (const auto& [width, height] : {std::pair{480, 360}, {240, 180}, {1920, 1080}, {360, 640}}) {
      envs::SceneView scene;
      scene.task = room.task;
      scene.env_dim = 10;
      int lost_by_default = 0, points = 0;
      for (double x = -room.inner; x <= room.inner + 1e-9; x += room.inner / 10) {
        for (double y = -room.inner; y <= room.inner + 1e-9; y += room.inner / 10) {
          if (room.octagon && std::abs(x) + std::abs(y) > room.inner * std::sqrt(2.0)) continue;
          for (const double z : {0.0, 2.0}) {
            scene.agent_position = {x, y, z};
            const double aspect = static_cast<double>(width) / height;
            const Pixel p = project(camera_for(scene, "arena", aspect), {x, y, z}, width, height);
            EXPECT_TRUE(in_frame(p, width, height))
                << room.task << " " << width << "x" << height << " (" << x << ", " << y << ", " << z
                << ") at pixel (" << p.x << ", " << p.y << ")";
            lost_by_default += !in_frame(project(camera_for(scene, "default", aspect), {x, y, z}, width, height),
                                         width, height);
            ++points;
          }
        }
      }
      EXPECT_GT(lost_by_default, 0) << room.task << " " << width << "x" << height << " of " << points;
    }
  }
  envs::SceneView run;
  run.task = "Run";
  run.env_dim = 250;
  for (const double x : {0.0, 57.3, 240.0}) {
    for (const double y : {-8.0, -2.0, 0.0, 2.0, 8.0}) {
      run.agent_position = {x, y, 0.5};
      const Pixel p = project(camera_for(run, "arena", 4.0 / 3), run.agent_position, 480, 360);
      EXPECT_TRUE(in_frame(p, 480, 360)) << "Run (" << x << ", " << y << ") at (" << p.x << ", " << p.y << ")";
    }
  }
}

}  // namespace
}  // namespace bsg::render
