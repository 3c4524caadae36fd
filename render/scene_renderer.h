// Draws a scene (envs/assembly/scene.h) with OpenGL 3.3 into an RGB image (and
// optionally depth): every collision object of the world from its Bullet
// shape (spheres, boxes, compounds, and every other convex shape: capsules,
// multi-spheres, convex hulls), the ground with a 1-m grid, and the task's
// markings, lit by one directional light. The palette (docs/rendering.md):
// agent blue, walls grey, other bodies (the Reach Box) orange, goal zone green,
// puddles and pillars purple, apples green, bombs red (the original's two
// colours), collected ones grey, safety boundaries red, the Circle's track yellow.
//
// Parameters:
//   width, height  image size in pixels, each in [1, kMaxSide]
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "render/camera.h"
#include "render/image.h"

namespace bsg::render {

// One point of a path drawn over the ground (trajectory plots): red where the
// step cost, blue where it did not.
struct PathPoint {
  double x = 0;
  double y = 0;
  bool cost = false;
};

class SceneRenderer {
 public:
  static constexpr int kMaxSide = 8192;

  // Creates the OpenGL context and its framebuffer; throws std::invalid_argument
  // for a size out of range, std::runtime_error (naming EGL) without a driver.
  SceneRenderer(int width, int height);
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  // Throws std::invalid_argument naming the side out of [1, kMaxSide].
  static void require_valid_size(int width, int height);

  int width() const;
  int height() const;

  // Draws `scene` as `camera` sees it into `image` (resized to height×width×3).
  // With `depth`, also writes each pixel's distance along the view axis in
  // metres (camera.far_m where nothing was hit), row 0 at the top.
  void draw(const envs::SceneView& scene, const Camera& camera, Image& image,
            std::vector<float>* depth = nullptr, std::span<const std::vector<PathPoint>> paths = {});

 private:
  struct Gl;  // every OpenGL object, behind the header so it needs no GL header
  std::unique_ptr<Gl> gl_;
};

}  // namespace bsg::render
