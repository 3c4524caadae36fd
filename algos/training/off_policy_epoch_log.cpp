#include "algos/training/off_policy_epoch_log.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "algos/core/epoch_statistics.h"
#include "algos/training/epoch_log.h"

namespace bsg::algos {
namespace {

// The one list of the columns, in order. With inputs (a row, collective) each column gets its
// value; without (the header of a layout) only its name and a 0.
std::vector<NamedScalar> off_policy_log_entries(const OffPolicyLogLayout& layout, const OffPolicyLogInputs* in,
                                                const MpiContext* mpi) {
  std::vector<NamedScalar> row;
  const auto add = [&row](std::string name, double value) { row.push_back({std::move(name), value}); };
  const auto value = [in](auto compute) { return in != nullptr ? static_cast<double>(compute()) : 0.0; };
  const auto pooled = [&](const std::string& prefix, const std::vector<double>* values) {
    PooledStatistics stats;
    if (in != nullptr) {
      stats = pool_statistics(
          Eigen::Map<const Eigen::VectorXd>(values->data(), static_cast<Eigen::Index>(values->size())), *mpi);
    }
    add(prefix + "_mean", stats.mean);
    add(prefix + "_std", stats.std);
    add(prefix + "_min", stats.min);
    add(prefix + "_max", stats.max);
  };
  const OffPolicyUpdateTally* tally = in != nullptr ? in->updates : nullptr;
  const double none = std::numeric_limits<double>::quiet_NaN();
  // A mean over this rank's gradient steps, averaged over ranks (every rank takes as many steps).
  const auto step_mean = [&](double steps, auto sum) {
    if (tally == nullptr) return 0.0;
    return steps > 0 ? mpi->average(sum() / steps) : none;
  };

  add("epoch", value([&] { return in->epoch; }));
  add("total_env_steps", value([&] { return static_cast<long long>(in->epoch + 1) * in->steps_per_epoch; }));
  pooled("episode_return", in != nullptr ? &in->episodes->returns : nullptr);
  pooled("episode_cost", in != nullptr ? &in->episodes->costs : nullptr);
  pooled("episode_length", in != nullptr ? &in->episodes->lengths : nullptr);
  add("episodes", value([&] { return in->episode_count; }));
  add("updates", value([&] { return tally->updates; }));
  add("reward_critic_loss", step_mean(value([&] { return tally->updates; }), [&] { return tally->reward_critic_loss; }));
  add("q_reward_mean", step_mean(value([&] { return tally->updates; }), [&] { return tally->reward_q; }));
  for (int i = 0; i < layout.critic_cost_count; ++i) {
    const std::string prefix = layout.prefixed_cost_critics ? "constraint_" + std::to_string(i + 1) + "_" : "";
    add(prefix + "cost_critic_loss",
        step_mean(value([&] { return tally->updates; }), [&] { return tally->cost_critic_losses(i); }));
    add(prefix + "q_cost_mean", step_mean(value([&] { return tally->updates; }), [&] { return tally->cost_qs(i); }));
  }
  add("actor_loss", step_mean(value([&] { return tally->actor_updates; }), [&] { return tally->actor_loss; }));
  if (layout.alpha) add("alpha", value([&] { return in->alpha; }));
  for (std::size_t i = 0; i < layout.multiplier_names.size(); ++i) {
    add(progress_column_name(layout.multiplier_names[i]), value([&] { return in->multipliers[i].value; }));
  }
  for (int i = 0; i < layout.per_constraint; ++i) {
    const std::string prefix = "constraint_" + std::to_string(i + 1) + "_";
    const std::size_t ii = static_cast<std::size_t>(i);
    add(prefix + "cost", value([&] { return in->constraints[ii].mean_episode_cost; }));
    add(prefix + "limit", value([&] { return in->constraints[ii].limit; }));
  }
  add("time_collect_s", value([&] { return in->collect_seconds; }));
  add("time_update_s", value([&] { return in->update_seconds; }));
  add("time_s", value([&] { return in->elapsed_seconds; }));
  add("fps", value([&] { return in->steps_per_epoch / std::max(in->epoch_seconds, 1e-9); }));
  const long long steps_so_far = in != nullptr ? static_cast<long long>(in->epoch + 1) * in->steps_per_epoch : 0;
  const double cumulative = value([&] { return in->training_cost->cumulative_cost; });
  add("cumulative_cost", cumulative);
  add("cost_rate", value([&] { return TrainingCost::rate(cumulative, steps_so_far); }));
  return row;
}

}  // namespace

std::vector<std::string> off_policy_log_columns(const OffPolicyLogLayout& layout) {
  return names_of(off_policy_log_entries(layout, nullptr, nullptr));
}

std::vector<NamedScalar> make_off_policy_log_row(const OffPolicyLogLayout& layout, const OffPolicyLogInputs& in,
                                                 const MpiContext& mpi) {
  if (in.episodes == nullptr || in.updates == nullptr || in.training_cost == nullptr) {
    throw std::invalid_argument("make_off_policy_log_row: missing inputs");
  }
  if (in.multipliers.size() != layout.multiplier_names.size() ||
      in.constraints.size() < static_cast<std::size_t>(layout.per_constraint) ||
      in.updates->cost_critic_losses.size() != layout.critic_cost_count ||
      in.updates->cost_qs.size() != layout.critic_cost_count) {
    throw std::invalid_argument("make_off_policy_log_row: the inputs do not fit the layout");
  }
  return off_policy_log_entries(layout, &in, &mpi);
}

}  // namespace bsg::algos
