#include "recording.h"

#include <CLI/CLI.hpp>

#include <ostream>

namespace bsg::cli {

// Forwards every call to both recorders (either may be absent), of a single- or multi-agent env.
class Recording::Fanout final : public render::EnvObserver, public render::MultiAgentEnvObserver {
 public:
  Fanout(render::VideoRecorder* video, render::TrajectoryRecorder* trajectories)
      : observers_{video, trajectories}, multi_agent_observers_{video, trajectories} {}
  void before_reset(const envs::Env& env) override { each([&](auto& o) { o.before_reset(env); }); }
  void after_reset(const envs::Env& env) override { each([&](auto& o) { o.after_reset(env); }); }
  void after_step(const envs::Env& env, const envs::StepResult& result) override {
    each([&](auto& o) { o.after_step(env, result); });
  }
  void before_destroy(const envs::Env& env) noexcept override { each([&](auto& o) { o.before_destroy(env); }); }
  void before_reset(const envs::MultiAgentEnv& env) override { each_multi_agent([&](auto& o) { o.before_reset(env); }); }
  void after_reset(const envs::MultiAgentEnv& env) override { each_multi_agent([&](auto& o) { o.after_reset(env); }); }
  void after_step(const envs::MultiAgentEnv& env, const envs::MultiAgentStepResult& result) override {
    each_multi_agent([&](auto& o) { o.after_step(env, result); });
  }
  void before_destroy(const envs::MultiAgentEnv& env) noexcept override {
    each_multi_agent([&](auto& o) { o.before_destroy(env); });
  }

 private:
  template <typename Call>
  void each(Call call) {
    for (render::EnvObserver* o : observers_) if (o != nullptr) call(*o);
  }
  template <typename Call>
  void each_multi_agent(Call call) {
    for (render::MultiAgentEnvObserver* o : multi_agent_observers_) if (o != nullptr) call(*o);
  }

  render::EnvObserver* observers_[2];
  render::MultiAgentEnvObserver* multi_agent_observers_[2];
};

void add_recording_options(CLI::App& command, RecordingArguments& args) {
  command.add_option("--video", args.video,
                     "write the episodes as an H.264 MP4 (one frame per step, captioned)");
  command.add_option("--trajectories", args.trajectories,
                     "write a PNG of each episode's path seen from above (red where it cost)");
  // A video exists to show the agent: its default camera keeps the whole arena
  // in view, while rgb_array (Python) and --picture keep the original's camera.
  args.render.camera = kVideoCamera;
  command
      .add_option("--camera", args.render.camera,
                  "--video camera:\n"
                  "  arena    the whole arena at the original's angle, the agent in view all the\n"
                  "           episode (Run: 16 m of lane around the agent)\n"
                  "  default  the original suite's camera of the task (Circle, Gather, Reach: fixed\n"
                  "           on the near half, the agent can leave the frame; Run: behind the agent)\n"
                  "  track    4 m from the agent, following it\n"
                  "  top      straight down over the arena (Run: 16 m x 8 m of lane)")
      ->capture_default_str();
  command.add_option("--width", args.render.width, "--video frame width")->capture_default_str();
  command.add_option("--height", args.render.height, "--video frame height")->capture_default_str();
}

Recording::Recording(const RecordingArguments& args) : args_(args) {
  if (!args.video.empty()) video_ = std::make_unique<render::VideoRecorder>(args.video, args.render);
  if (!args.trajectories.empty()) {
    trajectories_ = std::make_unique<render::TrajectoryRecorder>(args.trajectories);
  }
  fanout_ = std::make_unique<Fanout>(video_.get(), trajectories_.get());
}

Recording::~Recording() = default;

std::unique_ptr<envs::Env> Recording::wrap(std::unique_ptr<envs::Env> env) {
  if (!args_.any()) return env;
  return std::make_unique<render::ObservedEnv>(std::move(env), *fanout_);
}

std::unique_ptr<envs::MultiAgentEnv> Recording::wrap(std::unique_ptr<envs::MultiAgentEnv> env) {
  if (!args_.any()) return env;
  return std::make_unique<render::ObservedMultiAgentEnv>(std::move(env), *fanout_);
}

void Recording::finish(std::ostream& out) {
  if (video_) {
    const int frames = video_->close();
    out << "video " << args_.video << " (" << frames << " frames, " << args_.render.width << "x"
        << args_.render.height << ", camera " << args_.render.camera << ")\n";
  }
  if (trajectories_) {
    const int episodes = trajectories_->close();
    out << "trajectories " << args_.trajectories << " (" << episodes << " episodes)\n";
  }
}

}  // namespace bsg::cli
