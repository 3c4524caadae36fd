#include "render/episode_recorders.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "render/caption.h"
#include "envs/assembly/scene.h"
#include "render/image_grid.h"
#include "render/png_file.h"

namespace bsg::render {
namespace {

std::string formatted(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

// The caption's fields: "episode 3", "step 180" (when step >= 0), "return 257.0", "cost 12".
std::vector<std::string> caption_fields(int episode, int step, double episode_return, double cost) {
  std::vector<std::string> fields{"episode " + std::to_string(episode)};
  if (step >= 0) fields.push_back("step " + std::to_string(step));
  fields.push_back(formatted("return %.1f", episode_return));
  fields.push_back(formatted("cost %.0f", cost));
  return fields;
}

}  // namespace

VideoRecorder::VideoRecorder(const std::string& path, const RenderOptions& render,
                             const VideoOptions& video, bool caption)
    : renderer_(render), video_(path, render.width, render.height, video), caption_(caption) {}

void VideoRecorder::after_reset(const envs::Env& env) {
  ++episode_;
  step_ = 0;
  return_ = cost_ = 0;
  add_frame(env);
}

void VideoRecorder::after_step(const envs::Env& env, const envs::StepResult& result) {
  ++step_;
  return_ += result.reward;
  cost_ += result.cost;
  add_frame(env);
}

void VideoRecorder::add_frame(const envs::Env& env) {
  renderer_.render(env, frame_);
  if (caption_) draw_caption(frame_, caption_fields(episode_, step_, return_, cost_));
  video_.add_frame(frame_);
}

int VideoRecorder::close() {
  video_.close();
  return video_.frames();
}

namespace {
const std::string& writable(const std::string& path) {
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!file) throw std::runtime_error("cannot write PNG '" + path + "': " + std::strerror(errno));
  return path;
}
}  // namespace

TrajectoryRecorder::TrajectoryRecorder(std::string path)
    : path_(writable(path)), renderer_(kPanelWidth, kPanelHeight) {}

void TrajectoryRecorder::before_reset(const envs::Env& env) {
  if (in_episode_) finish_episode(env);
}

void TrajectoryRecorder::after_reset(const envs::Env& env) {
  in_episode_ = true;
  path_points_.clear();
  const envs::Vec3 p = env.state().agent_position;
  path_points_.push_back({p[0], p[1], false});
  episode_return_ = episode_cost_ = 0;
}

void TrajectoryRecorder::after_step(const envs::Env& env, const envs::StepResult& result) {
  const envs::Vec3 p = env.state().agent_position;
  path_points_.push_back({p[0], p[1], result.cost > 0});
  episode_return_ += result.reward;
  episode_cost_ += result.cost;
}

void TrajectoryRecorder::finish_episode(const envs::Env& env) {
  in_episode_ = false;
  const envs::SceneView scene = envs::scene_view(env);
  const double aspect = static_cast<double>(kPanelWidth) / kPanelHeight;
  Camera camera = camera_for(scene, "top", aspect);
  if (scene.task == "Run") {
    // The lane is 500 m long: frame the stretch the agent ran instead.
    double x0 = path_points_.front().x, x1 = x0, y0 = -3, y1 = 3;
    for (const PathPoint& p : path_points_) {
      x0 = std::min(x0, p.x);
      x1 = std::max(x1, p.x);
      y0 = std::min(y0, p.y - 1);
      y1 = std::max(y1, p.y + 1);
    }
    camera = top_camera_over(x0 - 2, x1 + 2, y0, y1, aspect);
  }
  Image& panel = panels_.emplace_back();
  const std::vector<PathPoint>* paths = &path_points_;
  renderer_.draw(scene, camera, panel, nullptr, {paths, 1});
  draw_caption(panel, caption_fields(static_cast<int>(panels_.size()), -1, episode_return_, episode_cost_));
}

void TrajectoryRecorder::before_destroy(const envs::Env& env) noexcept {
  try {
    if (in_episode_) finish_episode(env);
  } catch (...) {
    drawing_error_ = std::current_exception();
  }
}

int TrajectoryRecorder::close() {
  if (drawing_error_) std::rethrow_exception(drawing_error_);
  if (panels_.empty()) throw std::runtime_error("trajectories '" + path_ + "': no episode was played");
  write_png(path_, image_grid(panels_, std::min<int>(4, static_cast<int>(panels_.size())), 4));
  return static_cast<int>(panels_.size());
}

}  // namespace bsg::render
