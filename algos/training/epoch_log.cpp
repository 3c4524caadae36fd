#include "algos/training/epoch_log.h"

#include <cctype>
#include <map>
#include <stdexcept>

#include "algos/core/constraint_costs.h"

namespace bsg {
namespace {

void add(std::vector<NamedScalar>& row, std::string name, double value) { row.push_back({std::move(name), value}); }

void add_pooled(std::vector<NamedScalar>& row, const std::string& prefix, const PooledStatistics& stats,
                bool with_std) {
  add(row, prefix + "_mean", stats.mean);
  if (with_std) add(row, prefix + "_std", stats.std);
  add(row, prefix + "_min", stats.min);
  add(row, prefix + "_max", stats.max);
}

Eigen::VectorXd episode_field(const Buffer& buffer, double (*field)(const EpisodeStats&)) {
  const std::vector<EpisodeStats>& episodes = buffer.episodes();
  Eigen::VectorXd values(static_cast<Eigen::Index>(episodes.size()));
  for (std::size_t i = 0; i < episodes.size(); ++i) values[static_cast<Eigen::Index>(i)] = field(episodes[i]);
  return values;
}

}  // namespace

EpisodeStatistics pool_episode_statistics(const Buffer& buffer, const MpiContext& mpi, bool per_constraint) {
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

std::vector<std::string> epoch_log_columns(const EpochLogLayout& layout) {
  std::vector<std::string> columns{"epoch", "total_env_steps"};
  const auto pooled = [&columns](const std::string& prefix, bool with_std) {
    columns.push_back(prefix + "_mean");
    if (with_std) columns.push_back(prefix + "_std");
    columns.push_back(prefix + "_min");
    columns.push_back(prefix + "_max");
  };
  pooled("episode_return", true);
  pooled("episode_cost", true);
  pooled("episode_length", true);
  columns.emplace_back("episodes");
  pooled("value", false);
  pooled("advantage", false);
  pooled("cost_value", false);
  columns.insert(columns.end(), {"value_loss", "value_loss_delta"});
  if (layout.cost_value_loss) columns.insert(columns.end(), {"cost_value_loss", "cost_value_loss_delta"});
  columns.insert(columns.end(), {"exploration_std", "reward_scale_mean", "reward_scale_std"});
  for (const std::string& name : layout.diagnostic_names) columns.push_back(progress_column_name(name));
  for (int i = 1; i <= layout.per_constraint; ++i) {
    const std::string prefix = "constraint_" + std::to_string(i) + "_";
    for (const char* suffix : {"cost", "limit", "cumulative_cost", "cost_rate", "epochs_over_limit"}) {
      columns.push_back(prefix + suffix);
    }
    if (layout.constraint_cost_value_losses) {
      columns.push_back(prefix + "cost_value_loss");
      columns.push_back(prefix + "cost_value_loss_delta");
    }
  }
  columns.insert(columns.end(), {"time_collect_s", "time_update_s", "time_s", "fps"});
  if (layout.training_cost) columns.insert(columns.end(), {"cumulative_cost", "cost_rate"});
  return columns;
}

EpochLogLayout epoch_log_layout(const RunConfig& config, const OnPolicyAlgorithm& algorithm) {
  EpochLogLayout layout;
  layout.cost_value_loss = algorithm.uses_cost_value_function();
  layout.diagnostic_names = algorithm.diagnostic_names();
  const bool several = !config.constraints.empty();  // the trainer's per-constraint columns (trainer.cpp)
  layout.per_constraint = several ? constraint_count(config) : 0;
  layout.constraint_cost_value_losses = several && algorithm.uses_cost_value_function();
  return layout;
}

std::vector<NamedScalar> make_epoch_log_row(const EpochLogInputs& in, const MpiContext& mpi) {
  if (in.episodes == nullptr || in.buffer == nullptr || in.update == nullptr || in.value_fit == nullptr ||
      in.return_normalizer == nullptr) {
    throw std::invalid_argument("make_epoch_log_row: missing inputs");
  }
  std::vector<NamedScalar> row;
  add(row, "epoch", in.epoch);
  add(row, "total_env_steps", static_cast<double>(in.total_env_steps));
  add_pooled(row, "episode_return", in.episodes->episode_return, true);
  add_pooled(row, "episode_cost", in.episodes->episode_cost, true);
  add_pooled(row, "episode_length", in.episodes->episode_length, true);
  add(row, "episodes", static_cast<double>(in.episodes->episode_return.count));
  add_pooled(row, "value", pool_statistics(in.buffer->values(), mpi), false);
  add_pooled(row, "advantage", pool_statistics(in.buffer->advantages(), mpi), false);
  add_pooled(row, "cost_value", pool_statistics(in.buffer->cost_values(), mpi), false);

  // Rank-local losses, averaged over ranks in one reduction.
  double losses[4] = {in.value_fit->loss_before, in.value_fit->mean_minibatch_loss - in.value_fit->loss_before, 0, 0};
  if (in.cost_value_fit != nullptr) {
    losses[2] = in.cost_value_fit->loss_before;
    losses[3] = in.cost_value_fit->mean_minibatch_loss - in.cost_value_fit->loss_before;
  }
  mpi.average_in_place(losses, 4);
  add(row, "value_loss", losses[0]);
  add(row, "value_loss_delta", losses[1]);
  if (in.cost_value_fit != nullptr) {
    add(row, "cost_value_loss", losses[2]);
    add(row, "cost_value_loss_delta", losses[3]);
  }
  add(row, "exploration_std", in.exploration_std);
  add(row, "reward_scale_mean", in.return_normalizer->mean()[0]);
  add(row, "reward_scale_std", in.return_normalizer->std()[0]);

  // The common diagnostics are rank-local (averaged here); the rest agree on all ranks.
  const std::vector<NamedScalar>& diagnostics = in.update->diagnostics;
  const std::size_t common = std::min(kCommonDiagnosticCount, diagnostics.size());
  std::vector<double> local_common(common);
  for (std::size_t i = 0; i < common; ++i) local_common[i] = diagnostics[i].value;
  mpi.average_in_place(local_common.data(), local_common.size());
  for (std::size_t i = 0; i < diagnostics.size(); ++i) {
    add(row, progress_column_name(diagnostics[i].name), i < common ? local_common[i] : diagnostics[i].value);
  }

  if (!in.constraints.empty()) {
    if (in.training_cost == nullptr || in.training_cost->epochs_over_limit.size() != in.constraints.size()) {
      throw std::invalid_argument("make_epoch_log_row: the per-constraint columns need the training cost of every constraint");
    }
    const bool fit_losses = !in.constraint_cost_value_fits.empty();
    if (fit_losses && in.constraint_cost_value_fits.size() != in.constraints.size()) {
      throw std::invalid_argument("make_epoch_log_row: one cost value fit per constraint is needed");
    }
    // Rank-local losses, before and change, averaged over ranks in one reduction.
    std::vector<double> fit_loss(2 * in.constraint_cost_value_fits.size());
    for (std::size_t i = 0; i < in.constraint_cost_value_fits.size(); ++i) {
      const ValueFitStats& fit = in.constraint_cost_value_fits[i];
      fit_loss[2 * i] = fit.loss_before;
      fit_loss[2 * i + 1] = fit.mean_minibatch_loss - fit.loss_before;
    }
    if (fit_losses) mpi.average_in_place(fit_loss.data(), fit_loss.size());
    for (std::size_t i = 0; i < in.constraints.size(); ++i) {
      const std::string prefix = "constraint_" + std::to_string(i + 1) + "_";
      const double cumulative = in.training_cost->constraint_cumulative_costs[i];
      add(row, prefix + "cost", in.constraints[i].mean_episode_cost);
      add(row, prefix + "limit", in.constraints[i].limit);
      add(row, prefix + "cumulative_cost", cumulative);
      add(row, prefix + "cost_rate", TrainingCost::rate(cumulative, in.total_env_steps));
      add(row, prefix + "epochs_over_limit", static_cast<double>(in.training_cost->epochs_over_limit[i]));
      if (fit_losses) {
        add(row, prefix + "cost_value_loss", fit_loss[2 * i]);
        add(row, prefix + "cost_value_loss_delta", fit_loss[2 * i + 1]);
      }
    }
  }

  const double epoch_seconds = in.collect_seconds + in.update_seconds;
  add(row, "time_collect_s", in.collect_seconds);
  add(row, "time_update_s", in.update_seconds);
  add(row, "time_s", in.elapsed_seconds);
  add(row, "fps", epoch_seconds > 0 ? in.steps_per_epoch / epoch_seconds : 0.0);
  if (in.training_cost != nullptr) {  // safety during training, trailing so that older readers keep their columns
    add(row, "cumulative_cost", in.training_cost->cumulative_cost);
    add(row, "cost_rate", TrainingCost::rate(in.training_cost->cumulative_cost, in.total_env_steps));
  }
  // The layout a checkpoint's log is checked against must be the one written here.
  EpochLogLayout layout;
  layout.cost_value_loss = in.cost_value_fit != nullptr;
  for (const NamedScalar& diagnostic : in.update->diagnostics) layout.diagnostic_names.push_back(diagnostic.name);
  layout.per_constraint = static_cast<int>(in.constraints.size());
  layout.constraint_cost_value_losses = !in.constraint_cost_value_fits.empty();
  layout.training_cost = in.training_cost != nullptr;
  const std::vector<std::string> expected = epoch_log_columns(layout);
  bool same = expected.size() == row.size();
  for (std::size_t i = 0; same && i < row.size(); ++i) same = expected[i] == row[i].name;
  if (!same) throw std::logic_error("make_epoch_log_row: the row's columns differ from epoch_log_columns()");
  return row;
}

}  // namespace bsg
