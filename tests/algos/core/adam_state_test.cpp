// The Adam state codec (algos/core/adam_state.h) against the layouts written out by hand: the binary
// form is m, v, t as BinaryWriter writes them one by one; the entries are the names and order the
// checkpoints of the first-order policy and the Lagrange multiplier have always held.
#include "algos/core/adam_state.h"

#include <gtest/gtest.h>

#include <cmath>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/binary_io.h"

namespace bsg::algos {
namespace {

// An Adam two steps in, so that m, v and t are all non-trivial.
Adam stepped_adam(Eigen::Index size) {
  Adam adam(size, AdamOptions{.learning_rate = 0.01});
  Eigen::VectorXd parameters = Eigen::VectorXd::LinSpaced(size, -1.0, 1.0);
  adam.step(parameters, Eigen::VectorXd::LinSpaced(size, 0.5, 2.0));
  adam.step(parameters, Eigen::VectorXd::LinSpaced(size, -3.0, 1.0));
  return adam;
}

TEST(AdamStateBinary, IsFirstMomentThenSecondMomentThenStepCount) {
  const Adam adam = stepped_adam(3);
  BinaryWriter codec;
  save_adam_state(adam, codec);
  BinaryWriter by_hand;
  by_hand.write_vector(adam.first_moment());
  by_hand.write_vector(adam.second_moment());
  by_hand.write_i64(2);
  EXPECT_EQ(codec.bytes(), by_hand.bytes());
}

TEST(AdamStateBinary, RoundTripRestoresTheNextStepExactly) {
  Adam adam = stepped_adam(3);
  BinaryWriter writer;
  save_adam_state(adam, writer);
  Adam restored(3, AdamOptions{.learning_rate = 0.01});
  BinaryReader reader(writer.bytes(), "test");
  load_adam_state(restored, reader, "value net");
  reader.expect_end();
  Eigen::VectorXd a = Eigen::VectorXd::Ones(3), b = a;
  adam.step(a, Eigen::VectorXd::Constant(3, 0.7));
  restored.step(b, Eigen::VectorXd::Constant(3, 0.7));
  EXPECT_EQ(a, b);
  EXPECT_EQ(restored.step_count(), 3);
}

TEST(AdamStateBinary, ANegativeStepCountOrAnotherSizeFailsNamingTheOwner) {
  BinaryWriter negative;
  negative.write_vector(Eigen::VectorXd::Zero(2));
  negative.write_vector(Eigen::VectorXd::Zero(2));
  negative.write_i64(-1);
  Adam adam(2);
  BinaryReader reader(negative.bytes(), "file.bin");
  try {
    load_adam_state(adam, reader, "cost critic");
    FAIL() << "a negative step count was accepted";
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("cost critic Adam step count is negative"), std::string::npos) << e.what();
  }
  Adam larger(3);
  BinaryReader again(negative.bytes(), "file.bin");
  EXPECT_THROW(load_adam_state(larger, again, "actor"), CheckpointError);
}

TEST(AdamStateEntries, MomentsThenStepNameAOneParameterAdamsFields) {
  const Adam adam = stepped_adam(1);
  const std::vector<NamedScalar> entries =
      adam_state_entries(adam, "lagrange_multiplier_adam_", AdamEntryLayout::moments_then_step);
  const std::vector<NamedScalar> expected{{"lagrange_multiplier_adam_m", adam.first_moment()[0]},
                                          {"lagrange_multiplier_adam_v", adam.second_moment()[0]},
                                          {"lagrange_multiplier_adam_t", 2.0}};
  EXPECT_EQ(entries, expected);
  Adam restored(1);
  restore_adam_state_entries(restored, entries, "lagrange_multiplier_adam_", AdamEntryLayout::moments_then_step);
  EXPECT_EQ(restored.first_moment(), adam.first_moment());
  EXPECT_EQ(restored.second_moment(), adam.second_moment());
  EXPECT_EQ(restored.step_count(), 2);
}

TEST(AdamStateEntries, StepThenMomentsIndexEveryParameterAfterTheFirstStep) {
  const Adam adam = stepped_adam(2);
  const std::vector<NamedScalar> entries = adam_state_entries(adam, "policy_adam/", AdamEntryLayout::step_then_moments);
  const std::vector<NamedScalar> expected{{"policy_adam/t", 2.0},
                                          {"policy_adam/m/0", adam.first_moment()[0]},
                                          {"policy_adam/m/1", adam.first_moment()[1]},
                                          {"policy_adam/v/0", adam.second_moment()[0]},
                                          {"policy_adam/v/1", adam.second_moment()[1]}};
  EXPECT_EQ(entries, expected);
  EXPECT_EQ(saved_adam_parameters(entries, "policy_adam/"), 2);
  Adam restored(2);
  restore_adam_state_entries(restored, entries, "policy_adam/", AdamEntryLayout::step_then_moments);
  EXPECT_EQ(restored.first_moment(), adam.first_moment());
  EXPECT_EQ(restored.second_moment(), adam.second_moment());
  EXPECT_EQ(restored.step_count(), 2);
  // Before any step only t is saved.
  const std::vector<NamedScalar> fresh = adam_state_entries(Adam(2), "policy_adam/", AdamEntryLayout::step_then_moments);
  EXPECT_EQ(fresh, (std::vector<NamedScalar>{{"policy_adam/t", 0.0}}));
  EXPECT_EQ(saved_adam_parameters(fresh, "policy_adam/"), 0);
}

TEST(AdamStateEntries, ABadStepCountOrNameIsRefusedAndChangesNothing) {
  const Adam adam = stepped_adam(1);
  std::vector<NamedScalar> entries =
      adam_state_entries(adam, "lagrange_multiplier_adam_", AdamEntryLayout::moments_then_step);
  Adam target(1);
  for (const double t : {-1.0, 2.5, std::nan("")}) {
    std::vector<NamedScalar> bad = entries;
    bad[2].value = t;
    EXPECT_THROW(restore_adam_state_entries(target, bad, "lagrange_multiplier_adam_", AdamEntryLayout::moments_then_step),
                 std::invalid_argument);
  }
  std::vector<NamedScalar> renamed = entries;
  renamed[0].name = "lagrange_multiplier_adam_first";
  try {
    restore_adam_state_entries(target, renamed, "lagrange_multiplier_adam_", AdamEntryLayout::moments_then_step);
    FAIL() << "a renamed entry was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'lagrange_multiplier_adam_first'"), std::string::npos) << e.what();
  }
  EXPECT_EQ(target.step_count(), 0);
  EXPECT_EQ(target.first_moment()[0], 0.0);
  const std::vector<NamedScalar> policy = adam_state_entries(stepped_adam(2), "policy_adam/",
                                                             AdamEntryLayout::step_then_moments);
  Adam other_size(3);
  EXPECT_THROW(restore_adam_state_entries(other_size, policy, "policy_adam/", AdamEntryLayout::step_then_moments),
               std::invalid_argument);
  EXPECT_THROW(saved_adam_parameters(std::span(policy).first(4), "policy_adam/"), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::algos
