// `bsg eval RUN --video --trajectories` end to end on a tiny trained run, single- and
// multi-agent: the figures are those of a plain `bsg eval`, the MP4 holds one frame per reset
// and step of every episode, the PNG one 480×360 panel per episode.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "../cli/run_bsg.h"
#include "../test_support.h"
#include "render_test_support.h"

namespace bsg::render {
namespace {

TEST(EvalRecording, VideoAndTrajectoriesOfTheDeterministicPolicy) {
  BSG_RENDERER_OR_SKIP(probe, (RenderOptions{64, 48, "default"}));
  testing::TemporaryDirectory dir;
  const std::filesystem::path run_file = dir.path() / "run.yaml";
  testing::write_text_file(run_file,
                           "env_id: SafetyBallCircle-v0\nalg: lag-trpo\nseed: 3\nepochs: 1\n"
                           "steps_per_epoch: 1000\neval_episodes: 2\n");
  const std::string configs = std::string(" --configs ").append(BSG_SOURCE_DIR).append("/configs");
  ASSERT_EQ(testing::run_bsg("train " + run_file.string() + configs + " --quiet --out " + dir.str("run")).exit_code, 0);

  const testing::ProgramResult plain = testing::run_bsg("eval " + dir.str("run") + " --episodes 2");
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  const std::string video = dir.str("eval.mp4"), plot = dir.str("paths.png");
  const testing::ProgramResult recorded = testing::run_bsg(
      "eval " + dir.str("run") + " --episodes 2 --video " + video + " --trajectories " + plot +
      " --width 128 --height 96 --camera top");
  ASSERT_EQ(recorded.exit_code, 0) << recorded.output;
  // Recording changes nothing the evaluation computes.
  EXPECT_TRUE(testing::contains(recorded.output, plain.output));
  EXPECT_TRUE(testing::contains(recorded.output, "(502 frames, 128x96, camera top)"));
  EXPECT_TRUE(testing::contains(recorded.output, "trajectories " + plot + " (2 episodes)"));

  // SafetyBallCircle-v0 episodes run their 250 steps: 2 × (1 + 250) frames.
  EXPECT_EQ(testing::decode_video(video).size(), 502u);
  const Image panels = testing::read_png(plot);
  EXPECT_EQ(panels.width, 4 + 2 * (480 + 4));
  EXPECT_EQ(panels.height, 4 + 360 + 4);
}

// A MAPPO-L run on two Balls: the recording observes the multi-agent environment the family's
// evaluation plays (render/observed_multi_agent_env.h).
TEST(EvalRecording, VideoAndTrajectoriesOfAMultiAgentRun) {
  BSG_RENDERER_OR_SKIP(probe, (RenderOptions{64, 48, "default"}));
  testing::TemporaryDirectory dir;
  const std::string configs = std::string(" --configs ").append(BSG_SOURCE_DIR).append("/configs");
  ASSERT_EQ(testing::run_bsg("train --set env_id=SafetyBallCircle2-v0 --set alg=mappo-lag --set epochs=1 "
                             "--set steps_per_epoch=200 --set max_ep_len=100 --set hidden_sizes=[8] "
                             "--set policy_minibatch_size=200" +
                             configs + " --quiet --out " + dir.str("run"))
                .exit_code,
            0);
  const testing::ProgramResult plain = testing::run_bsg("eval " + dir.str("run") + " --episodes 2");
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_TRUE(testing::contains(plain.output, "agent_1 J (mean return) "));
  const std::string video = dir.str("eval.mp4"), plot = dir.str("paths.png");
  const testing::ProgramResult recorded = testing::run_bsg("eval " + dir.str("run") + " --episodes 2 --video " + video +
                                                           " --trajectories " + plot + " --width 128 --height 96");
  ASSERT_EQ(recorded.exit_code, 0) << recorded.output;
  EXPECT_TRUE(testing::contains(recorded.output, plain.output));
  // Episodes of max_ep_len = 100 steps: 2 × (1 + 100) frames.
  EXPECT_TRUE(testing::contains(recorded.output, "(202 frames, 128x96, camera arena)"));
  EXPECT_EQ(testing::decode_video(video).size(), 202u);
  const Image panels = testing::read_png(plot);
  EXPECT_EQ(panels.width, 4 + 2 * (480 + 4));
  EXPECT_EQ(panels.height, 4 + 360 + 4);
}

}  // namespace
}  // namespace bsg::render
