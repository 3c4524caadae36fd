// The recording options `bsg eval` and `bsg rollout` share: --video FILE.mp4,
// --trajectories FILE.png, --camera, --width, --height (render/, docs/rendering.md).
// A Recording wraps the environment the command plays so that its episodes
// are recorded without the playing loop knowing.
#pragma once

#include <iosfwd>
#include <memory>
#include <string>

#include "envs/env.h"
#include "envs/multi_agent_env.h"
#include "render/episode_recorders.h"

namespace CLI {
class App;
}

namespace bsg::cli {

// The camera of --video unless --camera says otherwise (render/camera.h).
inline constexpr const char* kVideoCamera = "arena";

struct RecordingArguments {
  std::string video;         // MP4 path; empty: no video
  std::string trajectories;  // PNG path; empty: no plot
  render::RenderOptions render;

  bool any() const { return !video.empty() || !trajectories.empty(); }
};

void add_recording_options(CLI::App& command, RecordingArguments& args);

class Recording {
 public:
  // Opens the outputs: a bad path, size or camera, or no EGL driver throws
  // here, before any episode runs.
  explicit Recording(const RecordingArguments& args);
  ~Recording();
  Recording(const Recording&) = delete;
  Recording& operator=(const Recording&) = delete;

  // `env` observed by every recorder asked for (unchanged if none).
  std::unique_ptr<envs::Env> wrap(std::unique_ptr<envs::Env> env);
  std::unique_ptr<envs::MultiAgentEnv> wrap(std::unique_ptr<envs::MultiAgentEnv> env);
  // Writes the files once the wrapped environment is destroyed; prints one line per file.
  void finish(std::ostream& out);

 private:
  // Forwards to both recorders.
  class Fanout;
  RecordingArguments args_;
  std::unique_ptr<render::VideoRecorder> video_;
  std::unique_ptr<render::TrajectoryRecorder> trajectories_;
  std::unique_ptr<Fanout> fanout_;
};

}  // namespace bsg::cli
