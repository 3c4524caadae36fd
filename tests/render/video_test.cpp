// Recorded MP4s decode: a lossless recording's frames equal render() exactly
// (the first one the frame after reset), a default (yuv420p) recording decodes
// to as many frames with the first within H.264's loss of render(); `bsg
// rollout --video` writes reset + step frames; bad --video input fails in one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

#include "../cli/run_bsg.h"
#include "../test_support.h"
#include "envs/env.h"
#include "render/camera.h"
#include "render/video_file.h"
#include "render_test_support.h"

namespace bsg::render {
namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("bsg_video_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

// Records the frame after reset and after each of `steps` steps.
std::vector<Image> record(EnvRenderer& renderer, VideoFile& video, int steps) {
  const auto env = envs::make("SafetyAntGather-v0");
  env->reset(2);
  const std::vector<double> action(static_cast<size_t>(env->spec().action_dim), 0.7);
  std::vector<Image> frames;
  renderer.render(*env, frames.emplace_back());
  video.add_frame(frames.back());
  for (int t = 0; t < steps; ++t) {
    env->step(action);
    renderer.render(*env, frames.emplace_back());
    video.add_frame(frames.back());
  }
  video.close();
  return frames;
}

TEST(Video, LosslessRecordingDecodesToTheRenderedFrames) {
  BSG_RENDERER_OR_SKIP(renderer, (RenderOptions{160, 120, "track"}));
  const std::string path = temp_path("lossless.mp4");
  VideoFile video(path, 160, 120, {.fps = 60, .lossless = true});
  const std::vector<Image> rendered = record(*renderer, video, 30);
  EXPECT_EQ(video.frames(), 31);
  const std::vector<Image> decoded = testing::decode_video(path);
  std::filesystem::remove(path);
  ASSERT_EQ(decoded.size(), rendered.size());
  for (size_t i = 0; i < decoded.size(); ++i) {
    ASSERT_EQ(decoded[i].width, 160);
    ASSERT_EQ(decoded[i].height, 120);
    EXPECT_EQ(decoded[i].rgb, rendered[i].rgb) << "frame " << i;
  }
}

TEST(Video, DefaultRecordingDecodesWithEveryFrameAndAFaithfulFirstFrame) {
  BSG_RENDERER_OR_SKIP(renderer, (RenderOptions{480, 360, "default"}));
  const std::string path = temp_path("default.mp4");
  VideoFile video(path, 480, 360);
  const std::vector<Image> rendered = record(*renderer, video, 40);
  const std::vector<Image> decoded = testing::decode_video(path);
  std::filesystem::remove(path);
  ASSERT_EQ(decoded.size(), 41u);
  ASSERT_EQ(decoded[0].rgb.size(), rendered[0].rgb.size());
  double squared_error = 0;
  for (size_t i = 0; i < decoded[0].rgb.size(); ++i) {
    const double d = double(decoded[0].rgb[i]) - double(rendered[0].rgb[i]);
    squared_error += d * d;
  }
  // PSNR = 10·log10(255² / MSE). 4:2:0 chroma halves the resolution of the
  // thin coloured lines (boundaries, the track); 30 dB is still a faithful picture.
  const double psnr = 10 * std::log10(255.0 * 255.0 / (squared_error / double(decoded[0].rgb.size())));
  EXPECT_GT(psnr, 30) << "first frame PSNR " << psnr << " dB";
}

TEST(Video, RolloutWritesOneFramePerResetAndStep) {
  BSG_RENDERER_OR_SKIP(probe, (RenderOptions{64, 48, "default"}));
  const std::string path = temp_path("rollout.mp4");
  // SafetyBallCircle-v0 episodes are 250 steps (bsg envs).
  const testing::ProgramResult result = testing::run_bsg(
      "rollout --env SafetyBallCircle-v0 --episodes 2 --seed 1 --video " + path +
      " --width 96 --height 64 --camera track");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const std::vector<Image> decoded = testing::decode_video(path);
  std::filesystem::remove(path);
  EXPECT_EQ(decoded.size(), 2u * (250 + 1));
  EXPECT_EQ(decoded.at(0).width, 96);
  EXPECT_EQ(decoded.at(0).height, 64);
  EXPECT_TRUE(testing::contains(result.output, "(502 frames, 96x64, camera track)"));
}

// A video exists to show the agent: without --camera it is the arena camera
// (render/camera.h), which keeps the whole arena in view; the first frame's
// agent pixels are there (the blue of the agent, render_test_support.h).
TEST(Video, DefaultCameraIsTheArenaAndShowsTheAgent) {
  BSG_RENDERER_OR_SKIP(probe, (RenderOptions{64, 48, "default"}));
  const std::string path = temp_path("arena.mp4");
  const testing::ProgramResult result = testing::run_bsg(
      "rollout --env SafetyBallGather-v0 --episodes 1 --seed 1 --video " + path);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(testing::contains(result.output, "camera arena)")) << result.output;
  const std::vector<Image> decoded = testing::decode_video(path);
  std::filesystem::remove(path);
  ASSERT_FALSE(decoded.empty());
  for (const size_t i : {size_t{0}, decoded.size() / 2, decoded.size() - 1}) {
    EXPECT_GT(testing::count_pixels(decoded[i], testing::is_agent_blue), 0) << "frame " << i;
  }
}

// `--help` of both recording commands says what every camera shows.
TEST(Video, HelpDescribesEveryCamera) {
  for (const std::string command : {"eval", "rollout"}) {
    const testing::ProgramResult result = testing::run_bsg(command + " --help");
    ASSERT_EQ(result.exit_code, 0) << result.output;
    for (const std::string& camera : camera_names()) {
      EXPECT_TRUE(testing::contains(result.output, "  " + camera + "  ")) << command << ": " << camera;
    }
    EXPECT_TRUE(testing::contains(result.output, "the original suite's camera")) << command;
  }
}

TEST(Video, BadInputFailsWithOneLine) {
  for (const auto& [arguments, message] :
       {std::pair{std::string("--video /nonexistent-folder/v.mp4"), std::string("cannot write video '/nonexistent-folder/v.mp4'")},
        {"--video " + temp_path("x.mp4") + " --camera side", "unknown camera 'side' (valid: default, arena, track, top)"},
        {"--video " + temp_path("x.mp4") + " --width 0", "width must be in [1, 8192], got 0"},
        {"--video " + temp_path("x.mp4") + " --height 100000", "height must be in [1, 8192], got 100000"},
        {"--trajectories /nonexistent-folder/t.png", "cannot write PNG '/nonexistent-folder/t.png'"}}) {
    const testing::ProgramResult result = testing::run_bsg("rollout --env SafetyBallRun-v0 " + arguments);
    EXPECT_NE(result.exit_code, 0) << arguments;
    EXPECT_TRUE(testing::contains(result.output, message)) << arguments;
    EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1) << result.output;
  }
}

TEST(Video, WithoutAnEglDriverTheErrorNamesEglAndWhatToInstall) {
  // glvnd finds no vendor library: what a machine without Mesa's EGL sees.
  const testing::ProgramResult result = testing::run_command(
      "env __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json " + std::string(BSG_BINARY) +
      " rollout --env SafetyBallRun-v0 --video " + temp_path("none.mp4"));
  std::filesystem::remove(temp_path("none.mp4"));
  EXPECT_NE(result.exit_code, 0);
  EXPECT_TRUE(testing::contains(result.output, "EGL"));
  EXPECT_TRUE(testing::contains(result.output, "apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri"));
  EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1) << result.output;
}

}  // namespace
}  // namespace bsg::render
