// Observers (observed_env.h) that record the episodes an environment plays:
//   VideoRecorder       one MP4 of every episode back to back: the frame after
//                       each reset and after every step (an episode of n steps
//                       gives n + 1 frames), captioned with the episode, step,
//                       return and cost so far
//   TrajectoryRecorder  a PNG with one top-down panel per episode: the arena at
//                       the episode's end and the agent's path, red where the
//                       step cost, blue elsewhere
// Both observe a multi-agent environment too (observed_multi_agent_env.h): the captions' return
// and cost are then the agents' mean (as a multi-agent evaluation's), and the trajectories hold one
// path per robot, red where the robot's agents' cost.
#pragma once

#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "render/env_renderer.h"
#include "render/observed_env.h"
#include "render/observed_multi_agent_env.h"
#include "render/scene_renderer.h"
#include "render/video_file.h"

namespace bsg::render {

class VideoRecorder final : public EnvObserver, public MultiAgentEnvObserver {
 public:
  // Opens the video (throws naming the path if it cannot be written) and the
  // renderer (throws naming EGL without a driver) before any episode runs.
  VideoRecorder(const std::string& path, const RenderOptions& render, const VideoOptions& video = {},
                bool caption = true);

  void after_reset(const envs::Env& env) override;
  void after_step(const envs::Env& env, const envs::StepResult& result) override;
  void after_reset(const envs::MultiAgentEnv& env) override;
  void after_step(const envs::MultiAgentEnv& env, const envs::MultiAgentStepResult& result) override;
  // Finishes the file; returns the number of frames written.
  int close();

 private:
  void start_episode();
  void add_frame();

  EnvRenderer renderer_;
  VideoFile video_;
  bool caption_;
  Image frame_;
  int episode_ = 0;
  int step_ = 0;
  double return_ = 0;
  double cost_ = 0;
};

class TrajectoryRecorder final : public EnvObserver, public MultiAgentEnvObserver {
 public:
  static constexpr int kPanelWidth = 480;
  static constexpr int kPanelHeight = 360;

  // Throws naming the path if it cannot be written (it is created empty here
  // so that a bad path fails before any episode runs), naming EGL without a driver.
  explicit TrajectoryRecorder(std::string path);

  void before_reset(const envs::Env& env) override;
  void after_reset(const envs::Env& env) override;
  void after_step(const envs::Env& env, const envs::StepResult& result) override;
  // Draws the last episode's panel.
  void before_destroy(const envs::Env& env) noexcept override;
  void before_reset(const envs::MultiAgentEnv& env) override;
  void after_reset(const envs::MultiAgentEnv& env) override;
  void after_step(const envs::MultiAgentEnv& env, const envs::MultiAgentStepResult& result) override;
  void before_destroy(const envs::MultiAgentEnv& env) noexcept override;
  // Writes the PNG once the observed environment is gone; returns the number
  // of episodes drawn. Throws naming the path, or what failed while drawing.
  int close();

 private:
  void start_episode(const std::vector<envs::EnvState>& robots);
  void add_step(const std::vector<envs::EnvState>& robots, const std::vector<bool>& robot_costs, double reward,
                double cost);
  void finish_episode(const envs::SceneView& scene);

  std::string path_;
  SceneRenderer renderer_;
  std::vector<std::vector<PathPoint>> paths_;  // one per robot
  bool in_episode_ = false;
  double episode_return_ = 0;
  double episode_cost_ = 0;
  std::vector<Image> panels_;
  std::exception_ptr drawing_error_;
};

}  // namespace bsg::render
