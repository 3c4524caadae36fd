#include "algos/training/epoch_log.h"

#include <cctype>
#include <map>
#include <stdexcept>

#include "algos/core/constraint_costs.h"
#include "algos/training/budget_decorator.h"

namespace bsg::algos {
namespace {

void add(std::vector<NamedScalar>& row, std::string name, double value) { row.push_back({std::move(name), value}); }

Eigen::VectorXd episode_field(const Buffer& buffer, double (*field)(const EpisodeStats&)) {
  const std::vector<EpisodeStats>& episodes = buffer.episodes();
  Eigen::VectorXd values(static_cast<Eigen::Index>(episodes.size()));
  for (std::size_t i = 0; i < episodes.size(); ++i) values[static_cast<Eigen::Index>(i)] = field(episodes[i]);
  return values;
}

}  // namespace

EpisodeStatistics pool_episode_statistics(const Buffer& buffer, const MpiContext& mpi, bool per_constraint,
                                          bool learner_signal) {
  EpisodeStatistics stats;
  stats.episode_return =
      pool_statistics(episode_field(buffer, [](const EpisodeStats& e) { return e.episode_return; }), mpi);
  stats.episode_cost = pool_statistics(episode_field(buffer, [](const EpisodeStats& e) { return e.episode_cost; }), mpi);
  stats.episode_length = pool_statistics(
      episode_field(buffer, [](const EpisodeStats& e) { return static_cast<double>(e.episode_length); }), mpi);
  if (per_constraint) {
    const std::vector<EpisodeStats>& episodes = buffer.episodes();
    Eigen::VectorXd values(static_cast<Eigen::Index>(episodes.size()));
    for (int c = 0; c < buffer.constraint_count(); ++c) {
      for (std::size_t i = 0; i < episodes.size(); ++i) {
        values[static_cast<Eigen::Index>(i)] = episodes[i].constraint_costs[static_cast<std::size_t>(c)];
      }
      stats.constraint_costs.push_back(pool_statistics(values, mpi));
    }
  }
  if (learner_signal) {
    stats.learner_return = pool_statistics(episode_field(buffer, [](const EpisodeStats& e) { return e.learner_return; }), mpi);
    stats.budget_spent = pool_statistics(
        episode_field(buffer, [](const EpisodeStats& e) { return e.budget_spent ? 1.0 : 0.0; }), mpi);
  }
  return stats;
}

std::string progress_column_name(std::string_view diagnostic_name) {
  static const std::map<std::string_view, std::string_view> kNames = {
      {"Loss/Pi", "policy_loss"},
      {"Loss/DeltaPi", "policy_loss_delta"},
      {"Entropy", "entropy"},
      {"KL", "kl"},
      {"PolicyRatio", "policy_ratio"},
      {"Misc/AcceptanceStep", "line_search_acceptance_step"},
      {"Misc/Alpha", "step_alpha"},
      {"Misc/FinalStepNorm", "final_step_norm"},
      {"Misc/gradient_norm", "gradient_norm"},
      {"Misc/xHx", "xFx"},
      {"Misc/H_inv_g", "cg_solution_norm"},
      {"LagrangeMultiplier", "lagrange_multiplier"},
      {"PID/P", "pid_p_term"},
      {"PID/I", "pid_i_term"},
      {"PID/D", "pid_d_term"},
      {"Misc/cost_gradient_norm", "cost_gradient_norm"},
      {"Misc/A", "cpo_A"},
      {"Misc/B", "cpo_B"},
      {"Misc/q", "cpo_q"},
      {"Misc/r", "cpo_r"},
      {"Misc/s", "cpo_s"},
      {"Misc/Lambda_star", "cpo_lambda_star"},
      {"Misc/Nu_star", "cpo_nu_star"},
      {"Misc/OptimCase", "cpo_optim_case"},
      {"Misc/StopIter", "policy_passes"},
      {"Misc/SecondStepStopIter", "projection_passes"},
  };
  if (const auto found = kNames.find(diagnostic_name); found != kNames.end()) return std::string(found->second);
  std::string name(diagnostic_name);
  for (char& c : name) c = c == '/' ? '_' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return name;
}

bool is_timing_column(std::string_view column) { return column.starts_with("time_") || column == "fps"; }

EpochLogLayout epoch_log_layout(const RunConfig& config, const OnPolicyAlgorithm& algorithm) {
  EpochLogLayout layout;
  layout.cost_value_loss = algorithm.uses_cost_value_function();
  layout.diagnostic_names = algorithm.diagnostic_names();
  const bool several = !config.constraints.empty();  // the trainer's per-constraint columns (trainer.cpp)
  layout.per_constraint = several ? constraint_count(config) : 0;
  layout.constraint_cost_value_losses = several && algorithm.uses_cost_value_function();
  layout.learner_signal = budget_method(config.alg) != BudgetMethod::none;
  return layout;
}

namespace {

// The one list of progress.csv's columns, in order. The layout decides which
// columns there are; with inputs (a row, collective) each column gets its
// value, without (the header of a layout) only its name and a 0.
std::vector<NamedScalar> epoch_log_entries(const EpochLogLayout& layout, const EpochLogInputs* in,
                                           const MpiContext* mpi) {
  std::vector<NamedScalar> row;
  const auto value = [in](auto compute) { return in != nullptr ? static_cast<double>(compute()) : 0.0; };
  const auto pooled = [&row, in](const std::string& prefix, bool with_std, auto pool) {
    const PooledStatistics stats = in != nullptr ? pool() : PooledStatistics{};
    add(row, prefix + "_mean", stats.mean);
    if (with_std) add(row, prefix + "_std", stats.std);
    add(row, prefix + "_min", stats.min);
    add(row, prefix + "_max", stats.max);
  };
  add(row, "epoch", value([&] { return in->epoch; }));
  add(row, "total_env_steps", value([&] { return in->total_env_steps; }));
  pooled("episode_return", true, [&] { return in->episodes->episode_return; });
  pooled("episode_cost", true, [&] { return in->episodes->episode_cost; });
  pooled("episode_length", true, [&] { return in->episodes->episode_length; });
  add(row, "episodes", value([&] { return in->episodes->episode_return.count; }));
  if (layout.learner_signal) {
    add(row, "learner_return_mean", value([&] { return in->episodes->learner_return->mean; }));
    add(row, "budget_spent_fraction", value([&] { return in->episodes->budget_spent->mean; }));
  }
  pooled("value", false, [&] { return pool_statistics(in->buffer->values(), *mpi); });
  pooled("advantage", false, [&] { return pool_statistics(in->buffer->advantages(), *mpi); });
  pooled("cost_value", false, [&] { return pool_statistics(in->buffer->cost_values(), *mpi); });

  // Rank-local losses, averaged over ranks in one reduction.
  double losses[4] = {0, 0, 0, 0};
  if (in != nullptr) {
    losses[0] = in->value_fit->loss_before;
    losses[1] = in->value_fit->mean_minibatch_loss - in->value_fit->loss_before;
    if (in->cost_value_fit != nullptr) {
      losses[2] = in->cost_value_fit->loss_before;
      losses[3] = in->cost_value_fit->mean_minibatch_loss - in->cost_value_fit->loss_before;
    }
    mpi->average_in_place(losses, 4);
  }
  add(row, "value_loss", losses[0]);
  add(row, "value_loss_delta", losses[1]);
  if (layout.cost_value_loss) {
    add(row, "cost_value_loss", losses[2]);
    add(row, "cost_value_loss_delta", losses[3]);
  }
  add(row, "exploration_std", value([&] { return in->exploration_std; }));
  add(row, "reward_scale_mean", value([&] { return in->return_normalizer->mean()[0]; }));
  add(row, "reward_scale_std", value([&] { return in->return_normalizer->std()[0]; }));

  // The common diagnostics are rank-local (averaged here); the rest agree on all ranks.
  const std::size_t common = std::min(kCommonDiagnosticCount, layout.diagnostic_names.size());
  std::vector<double> local_common(common, 0.0);
  if (in != nullptr) {
    for (std::size_t i = 0; i < common; ++i) local_common[i] = in->update->diagnostics[i].value;
    mpi->average_in_place(local_common.data(), local_common.size());
  }
  for (std::size_t i = 0; i < layout.diagnostic_names.size(); ++i) {
    add(row, progress_column_name(layout.diagnostic_names[i]),
        i < common ? local_common[i] : value([&] { return in->update->diagnostics[i].value; }));
  }

  if (layout.per_constraint > 0) {
    const auto constraints = static_cast<std::size_t>(layout.per_constraint);
    // Rank-local V_Ci losses, before and change, averaged over ranks in one reduction.
    std::vector<double> fit_loss(layout.constraint_cost_value_losses ? 2 * constraints : 0, 0.0);
    if (in != nullptr && layout.constraint_cost_value_losses) {
      for (std::size_t i = 0; i < constraints; ++i) {
        const ValueFitStats& fit = in->constraint_cost_value_fits[i];
        fit_loss[2 * i] = fit.loss_before;
        fit_loss[2 * i + 1] = fit.mean_minibatch_loss - fit.loss_before;
      }
      mpi->average_in_place(fit_loss.data(), fit_loss.size());
    }
    for (std::size_t i = 0; i < constraints; ++i) {
      const std::string prefix = "constraint_" + std::to_string(i + 1) + "_";
      const double cumulative = value([&] { return in->training_cost->constraint_cumulative_costs[i]; });
      add(row, prefix + "cost", value([&] { return in->constraints[i].mean_episode_cost; }));
      add(row, prefix + "limit", value([&] { return in->constraints[i].limit; }));
      add(row, prefix + "cumulative_cost", cumulative);
      add(row, prefix + "cost_rate", value([&] { return TrainingCost::rate(cumulative, in->total_env_steps); }));
      add(row, prefix + "epochs_over_limit", value([&] { return in->training_cost->epochs_over_limit[i]; }));
      if (layout.constraint_cost_value_losses) {
        add(row, prefix + "cost_value_loss", fit_loss[2 * i]);
        add(row, prefix + "cost_value_loss_delta", fit_loss[2 * i + 1]);
      }
    }
  }

  const double epoch_seconds = value([&] { return in->collect_seconds + in->update_seconds; });
  add(row, "time_collect_s", value([&] { return in->collect_seconds; }));
  add(row, "time_update_s", value([&] { return in->update_seconds; }));
  add(row, "time_s", value([&] { return in->elapsed_seconds; }));
  add(row, "fps", epoch_seconds > 0 ? in->steps_per_epoch / epoch_seconds : 0.0);
  if (layout.training_cost) {  // safety during training, trailing so that older readers keep their columns
    const double cumulative = value([&] { return in->training_cost->cumulative_cost; });
    add(row, "cumulative_cost", cumulative);
    add(row, "cost_rate", value([&] { return TrainingCost::rate(cumulative, in->total_env_steps); }));
  }
  return row;
}

}  // namespace

std::vector<std::string> epoch_log_columns(const EpochLogLayout& layout) {
  std::vector<std::string> columns;
  for (NamedScalar& entry : epoch_log_entries(layout, nullptr, nullptr)) columns.push_back(std::move(entry.name));
  return columns;
}

std::vector<NamedScalar> make_epoch_log_row(const EpochLogInputs& in, const MpiContext& mpi) {
  if (in.episodes == nullptr || in.buffer == nullptr || in.update == nullptr || in.value_fit == nullptr ||
      in.return_normalizer == nullptr) {
    throw std::invalid_argument("make_epoch_log_row: missing inputs");
  }
  if (!in.constraints.empty()) {
    if (in.training_cost == nullptr || in.training_cost->epochs_over_limit.size() != in.constraints.size()) {
      throw std::invalid_argument("make_epoch_log_row: the per-constraint columns need the training cost of every constraint");
    }
    if (!in.constraint_cost_value_fits.empty() && in.constraint_cost_value_fits.size() != in.constraints.size()) {
      throw std::invalid_argument("make_epoch_log_row: one cost value fit per constraint is needed");
    }
  }
  // The layout the inputs make: the same columns a checkpoint's log is checked against.
  EpochLogLayout layout;
  layout.cost_value_loss = in.cost_value_fit != nullptr;
  for (const NamedScalar& diagnostic : in.update->diagnostics) layout.diagnostic_names.push_back(diagnostic.name);
  layout.per_constraint = static_cast<int>(in.constraints.size());
  layout.constraint_cost_value_losses = !in.constraint_cost_value_fits.empty();
  layout.training_cost = in.training_cost != nullptr;
  layout.learner_signal = in.episodes->learner_return.has_value() && in.episodes->budget_spent.has_value();
  return epoch_log_entries(layout, &in, &mpi);
}

}  // namespace bsg::algos
