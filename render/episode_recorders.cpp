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
  start_episode();
  renderer_.render(env, frame_);
  add_frame();
}

void VideoRecorder::after_step(const envs::Env& env, const envs::StepResult& result) {
  ++step_;
  return_ += result.reward;
  cost_ += result.cost;
  renderer_.render(env, frame_);
  add_frame();
}

void VideoRecorder::after_reset(const envs::MultiAgentEnv& env) {
  start_episode();
  renderer_.render(env, frame_);
  add_frame();
}

void VideoRecorder::after_step(const envs::MultiAgentEnv& env, const envs::MultiAgentStepResult& result) {
  ++step_;
  const double n = static_cast<double>(result.rewards.size());
  for (std::size_t i = 0; i < result.rewards.size(); ++i) {
    return_ += result.rewards[i] / n;  // the agents' mean, summed as the evaluation sums it
    cost_ += result.costs[i] / n;
  }
  renderer_.render(env, frame_);
  add_frame();
}

void VideoRecorder::start_episode() {
  ++episode_;
  step_ = 0;
  return_ = cost_ = 0;
}

void VideoRecorder::add_frame() {
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

namespace {

// A single-agent environment as one robot.
std::vector<envs::EnvState> robot_of(const envs::Env& env) { return {env.state()}; }

// Whether each robot's agents cost in this step: its own agent's cost, or, for one robot split into
// agents (docs/multi_agent.md#the-split-ant), any agent's.
std::vector<bool> robot_costs(const envs::MultiAgentEnv& env, const envs::MultiAgentStepResult& result) {
  const std::size_t robots = static_cast<std::size_t>(env.spec().bodies);
  std::vector<bool> costs(robots, false);
  for (std::size_t i = 0; i < result.costs.size(); ++i) {
    const std::size_t robot = robots == result.costs.size() ? i : 0;
    if (result.costs[i] > 0) costs[robot] = true;
  }
  return costs;
}

}  // namespace

void TrajectoryRecorder::before_reset(const envs::Env& env) {
  if (in_episode_) finish_episode(envs::scene_view(env));
}

void TrajectoryRecorder::after_reset(const envs::Env& env) { start_episode(robot_of(env)); }

void TrajectoryRecorder::after_step(const envs::Env& env, const envs::StepResult& result) {
  add_step(robot_of(env), {result.cost > 0}, result.reward, result.cost);
}

void TrajectoryRecorder::before_destroy(const envs::Env& env) noexcept {
  try {
    if (in_episode_) finish_episode(envs::scene_view(env));
  } catch (...) {
    drawing_error_ = std::current_exception();
  }
}

void TrajectoryRecorder::before_reset(const envs::MultiAgentEnv& env) {
  if (in_episode_) finish_episode(envs::scene_view(env));
}

void TrajectoryRecorder::after_reset(const envs::MultiAgentEnv& env) { start_episode(env.body_states()); }

void TrajectoryRecorder::after_step(const envs::MultiAgentEnv& env, const envs::MultiAgentStepResult& result) {
  double reward = 0, cost = 0;
  const double n = static_cast<double>(result.rewards.size());
  for (std::size_t i = 0; i < result.rewards.size(); ++i) {
    reward += result.rewards[i] / n;  // the agents' mean
    cost += result.costs[i] / n;
  }
  add_step(env.body_states(), robot_costs(env, result), reward, cost);
}

void TrajectoryRecorder::before_destroy(const envs::MultiAgentEnv& env) noexcept {
  try {
    if (in_episode_) finish_episode(envs::scene_view(env));
  } catch (...) {
    drawing_error_ = std::current_exception();
  }
}

void TrajectoryRecorder::start_episode(const std::vector<envs::EnvState>& robots) {
  in_episode_ = true;
  paths_.assign(robots.size(), {});
  for (std::size_t r = 0; r < robots.size(); ++r) {
    const envs::Vec3& p = robots[r].agent_position;
    paths_[r].push_back({p[0], p[1], false});
  }
  episode_return_ = episode_cost_ = 0;
}

void TrajectoryRecorder::add_step(const std::vector<envs::EnvState>& robots, const std::vector<bool>& robot_costs,
                                  double reward, double cost) {
  for (std::size_t r = 0; r < robots.size(); ++r) {
    const envs::Vec3& p = robots[r].agent_position;
    paths_[r].push_back({p[0], p[1], robot_costs[r]});
  }
  episode_return_ += reward;
  episode_cost_ += cost;
}

void TrajectoryRecorder::finish_episode(const envs::SceneView& scene) {
  in_episode_ = false;
  const double aspect = static_cast<double>(kPanelWidth) / kPanelHeight;
  Camera camera = camera_for(scene, "top", aspect);
  if (scene.task == "Run") {
    // The lane is 500 m long: frame the stretch the robots ran instead.
    double x0 = paths_.front().front().x, x1 = x0, y0 = -3, y1 = 3;
    for (const std::vector<PathPoint>& path : paths_) {
      for (const PathPoint& p : path) {
        x0 = std::min(x0, p.x);
        x1 = std::max(x1, p.x);
        y0 = std::min(y0, p.y - 1);
        y1 = std::max(y1, p.y + 1);
      }
    }
    camera = top_camera_over(x0 - 2, x1 + 2, y0, y1, aspect);
  }
  Image& panel = panels_.emplace_back();
  renderer_.draw(scene, camera, panel, nullptr, paths_);
  draw_caption(panel, caption_fields(static_cast<int>(panels_.size()), -1, episode_return_, episode_cost_));
}

int TrajectoryRecorder::close() {
  if (drawing_error_) std::rethrow_exception(drawing_error_);
  if (panels_.empty()) throw std::runtime_error("trajectories '" + path_ + "': no episode was played");
  write_png(path_, image_grid(panels_, std::min<int>(4, static_cast<int>(panels_.size())), 4));
  return static_cast<int>(panels_.size());
}

}  // namespace bsg::render
