#include "render/env_renderer.h"

#include <algorithm>
#include <stdexcept>

#include "render/camera.h"
#include "envs/assembly/scene.h"

namespace bsg::render {

void require_valid(const RenderOptions& options) {
  SceneRenderer::require_valid_size(options.width, options.height);
  require_camera_name(options.camera);
}

namespace {
const RenderOptions& checked(const RenderOptions& options) {
  require_valid(options);
  return options;
}
}  // namespace

EnvRenderer::EnvRenderer(const RenderOptions& options)
    : options_(checked(options)), renderer_(options.width, options.height) {}

void EnvRenderer::render(const envs::Env& env, Image& image, std::vector<float>* depth) {
  draw(envs::scene_view(env), image, depth);
}

void EnvRenderer::render(const envs::MultiAgentEnv& env, Image& image, std::vector<float>* depth) {
  draw(envs::scene_view(env), image, depth);
}

void EnvRenderer::draw(const envs::SceneView& scene, Image& image, std::vector<float>* depth) {
  const double aspect = static_cast<double>(options_.width) / options_.height;
  renderer_.draw(scene, camera_for(scene, options_.camera, aspect), image, depth);
}

}  // namespace bsg::render
