// The schema table: every configuration key, put together from the rows of
// RunConfig's own keys (here) and those of its groups (common/trust_region_keys.cpp,
// multiplier_keys.cpp, first_order_keys.cpp, off_policy_keys.cpp), in one fixed
// order. Defaults are not here but in configs/ (the layer named in the second
// column provides them); RunConfig's member initialisers repeat the TRPO /
// SafetyBallCircle-v0 ones.
#include "common/run_config_schema.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <type_traits>
#include <variant>

#include "common/config_error.h"
#include "common/config_key_rows.h"
#include "common/message_text.h"
#include "common/config_scalar.h"
#include "common/foreign_key_spellings.h"

namespace bsg {

namespace {

using namespace key_rows;  // NOLINT: the row vocabulary of this file (common/config_key_rows.h)

// clang-format off
// The rows of RunConfig's own keys: those before the families' groups and those after them.
std::vector<ConfigKeyRow> leading_rows() {
  using L = ConfigLayer;
  using R = RunConfig;
  using N = NumericRange;
  constexpr AlgorithmSet all = kAllAlgorithms;
  return {
    // --- run ---
    text("env_id", field<&R::env_id>(), L::run,
         "environment id, e.g. SafetyBallCircle-v0 (report Table 3)"),
    choice("alg", enum_access<&R::alg>(), kAlgorithmNames, L::run, all,
           "algorithm: trpo, lag-trpo (TRPO-L), cpo, pdo, pcpo, the first-order ppo, ppo-lag, focops, cup, or the "
           "off-policy sac, td3, ddpg, sac-lag, td3-lag, ddpg-lag"),
    integer("seed", field<&R::seed>(), L::run, N::closed(0, 4294967295.0), all,
            "base seed; per-rank and per-environment seeds are derived from it (seeding.h)"),
    text("log_dir", field<&R::log_dir>(), L::run,
         "directory under which the run directory is created"),
    boolean("tensorboard", field<&R::tensorboard>(), L::run, all,
            "write TensorBoard event files beside progress.csv (its columns per epoch); config.yaml names the key "
            "only when false"),
    choice("physics", enum_access<&R::physics>(), kPhysicsModelNames, L::run, all,
           "faithful (the original's model) or lean (equivalent, faster; the Ant and the Car)"),
    boolean("joint_control", field<&R::joint_control>(), L::run, kOnPolicy | kOffPolicy,
            "on a multi-agent env_id: one policy controls every agent (the agents' observations and actions "
            "concatenated, reward and cost the agents' means); config.yaml names the key only when true"),
    choice("learner", enum_access<&R::learner>(), kLearnerNames, L::run, all,
           "preset: faithful (the original's learner) or corrected (every corrected switch on: Q1, Q4, Q5, "
           "Q10, Q19, Q20; a switch the run file or --set names itself keeps that value)"),
    mapping("env", field<&R::env>(), L::run, all,
            "environment parameters, e.g. {bombs: 12} (`bsg envs --describe ID` lists them)"),
    constraint_list("constraints", field<&R::constraints>(), all,
                    "several constraints, each summing named cost terms (or all) against its own limit: "
                    "[{terms: [cost_outside_bounds], limit: 20}, ...]; absent: the cost against cost_limit"),
    // --- environment (report Table 3, docs/reproducing.md#environment-settings) ---
    real("cost_limit", field<&R::cost_limit>(), L::environment, N::at_least(0), all,
         "d: limit on the undiscounted episode cost"),
    integer("epochs", field<&R::epochs>(), L::environment, N::closed(1, kIntMax), all,
            "E: number of training epochs"),
    integer("steps_per_epoch", field<&R::steps_per_epoch>(), L::environment, N::closed(1, kIntMax), all,
            "B: environment steps per epoch, summed over all MPI ranks"),
    integer("max_ep_len", field<&R::max_ep_len>(), L::environment, N::closed(1, kIntMax), all,
            "maximum episode length in steps (the environment's time limit)"),
    // --- networks (docs/algorithms.md#networks) ---
    integer_list("hidden_sizes", field<&R::hidden_sizes>(), L::algorithm, N::closed(1, 4096), all,
                 "hidden layer widths of the policy net and both value nets"),
    choice("activation", enum_access<&R::activation>(), kActivationNames, L::algorithm, all,
           "hidden-layer activation of all nets"),
    boolean("zero_bias_init", field<&R::zero_bias_init>(), L::algorithm, all,
            "Q1: zero initial biases (report) instead of uniform +-1/sqrt(fan_in) (original)"),
    choice("dtype", enum_access<&R::dtype>(), kDtypeNames, L::algorithm, all,
           "arithmetic of the networks' batch passes (surrogate, gradients, Fisher products, line search, "
           "value fits): float32 (the original's PyTorch default; faster, learning within seed spread) or "
           "float64; parameters, optimiser moments and CG vectors stay float64"),
    // --- returns, advantages, normalisation (docs/algorithms.md#normalisers, #rollout-and-gae) ---
    real("gamma", field<&R::gamma>(), L::algorithm, N::open_closed(0, 1),
         all & ~(algorithm_bit(Algorithm::bc_all) | algorithm_bit(Algorithm::bc_safe)),
         "discount factor for rewards and costs"),
    real("lam", field<&R::lam>(), L::algorithm, N::closed(0, 1), kOnPolicy | kMultiAgent,
         "GAE lambda for reward advantages"),
    real("lam_c", field<&R::lam_c>(), L::algorithm, N::closed(0, 1), kOnPolicy | kMultiAgent,
         "GAE lambda for cost advantages"),
    boolean("use_exploration_noise_anneal", field<&R::use_exploration_noise_anneal>(), L::algorithm, kOnPolicy,
            "anneal the exploration std: sigma_k = 0.499 (1 - k/E) + 0.01 (else fixed 0.5)"),
    integer("exploration_anneal_epochs", field<&R::exploration_anneal_epochs>(), L::algorithm, N::closed(0, kIntMax), kOnPolicy,
            "n > 0: the annealing ends at epoch n, sigma_k = 0.499 (1 - min(k, n)/n) + 0.01, and sigma holds "
            "0.01 for the epochs after it; 0 = E, the original's schedule; at most epochs"),
    real("exploration_std_floor", field<&R::exploration_std_floor>(), L::algorithm, N::at_least(0), kOnPolicy,
         "sigma_k = max(annealed sigma_k, floor): the noise never falls below the floor (keeps room for a KL "
         "step to move the mean action late in training); 0 = no floor (original)"),
    boolean("use_standardized_obs", field<&R::use_standardized_obs>(), L::algorithm, kOnPolicy | kMultiAgent,
            "normalise observations by the running mean/std"),
    boolean("use_reward_scaling", field<&R::use_reward_scaling>(), L::algorithm, kOnPolicy,
            "divide rewards by the running std of discounted returns, clip to +-10"),
    boolean("use_standardized_advantages", field<&R::use_standardized_advantages>(), L::algorithm, kOnPolicy,
            "Q6: standardise advantages (the original never does)"),
    boolean("center_advantages", field<&R::center_advantages>(), L::algorithm, kOnPolicy,
            "Q6: subtract the batch mean of the reward and cost advantages, keeping their scale "
            "(original: not centred; implied by use_standardized_advantages)"),
    real("obs_clip", field<&R::obs_clip>(), L::algorithm, N::at_least(0), kOnPolicy | kMultiAgent,
         "Q3: clip normalised observations to +-obs_clip; 0 = no clipping (original)"),
    boolean("exact_parallel_variance", field<&R::exact_parallel_variance>(), L::algorithm, kOnPolicy | kMultiAgent,
            "Q4: Chan's exact parallel variance instead of the original's update"),
    boolean("consistent_return_statistic", field<&R::consistent_return_statistic>(), L::algorithm, kOnPolicy,
            "Q5: the return statistic's bootstrap value in raw units, V (s_ret + 1e-5), as the rewards "
            "(original: V's scaled value)"),
    boolean("rescale_value_output", field<&R::rescale_value_output>(), L::algorithm, kOnPolicy,
            "Q19: when the return statistic changes, scale V's output layer by old/new std so that "
            "V's predictions in raw units are kept (PopArt)"),
    integer("reward_scale_warmup_epochs", field<&R::reward_scale_warmup_epochs>(), L::algorithm, N::closed(0, kIntMax), kOnPolicy,
            "update the return statistic only in the first n epochs, then keep it; 0 = every epoch (original)"),
    boolean("timeout_bootstrap", field<&R::timeout_bootstrap>(), L::algorithm, kOnPolicy | kMultiAgent,
            "bootstrap with V (V_C) of the next observation at a time-out (original); false: as a terminal"),
    boolean("value_time_input", field<&R::value_time_input>(), L::algorithm, kOnPolicy,
            "Q20: V and V_C also see the fraction of the time limit left, (max_ep_len - t)/max_ep_len at "
            "episode step t; false: the observation alone (original)"),
  };
}

std::vector<ConfigKeyRow> trailing_rows() {
  using L = ConfigLayer;
  using R = RunConfig;
  using N = NumericRange;
  constexpr AlgorithmSet all = kAllAlgorithms;
  return {
    // --- value networks (docs/algorithms.md#value-fits) ---
    boolean("use_cost_value_function", field<&R::use_cost_value_function>(), L::algorithm, kOnPolicy,
            "train the cost value net V_C"),
    real("vf_lr", field<&R::vf_lr>(), L::algorithm, N::above(0), kOnPolicy | kMultiAgent,
         "Adam learning rate of the value nets"),
    integer("train_v_iterations", field<&R::train_v_iterations>(), L::algorithm, N::closed(1, 10000), kOnPolicy | kMultiAgent,
            "Q15: passes over the local batch per epoch when fitting the value nets"),
    integer("num_mini_batches", field<&R::num_mini_batches>(), L::algorithm, N::closed(1, 100000), kOnPolicy | kMultiAgent,
            "Q15: minibatches per pass; minibatch size floor(N / num_mini_batches) per rank"),
    // --- bookkeeping (docs/algorithms.md#the-epoch-loop, docs/reproducing.md#evaluation) ---
    integer("save_freq", field<&R::save_freq>(), L::algorithm, N::closed(1, kIntMax), all,
            "save a checkpoint every save_freq epochs and after the last"),
    integer("check_freq", field<&R::check_freq>(), L::algorithm, N::closed(1, kIntMax), kOnPolicy | kMultiAgent,
            "check that parameters agree across ranks every check_freq epochs"),
    integer("eval_episodes", field<&R::eval_episodes>(), L::algorithm, N::closed(0, kIntMax), all,
            "evaluation episodes after training, split over ranks"),
    boolean("sampled_evaluation", field<&R::sampled_evaluation>(), L::algorithm, kOnPolicy,
            "evaluate the policy as it was trained, a = mu + sigma eps at the last epoch's sigma, with "
            "its own noise stream; false = the deterministic mean action (original)"),
  };
}
// clang-format on

// The one table, in the order config.yaml, --print-config and configs/README.md show.
const std::vector<ConfigKeyRow>& schema_rows() {
  static const std::vector<ConfigKeyRow> rows = [] {
    std::vector<ConfigKeyRow> all;
    for (std::vector<ConfigKeyRow> part : {leading_rows(), trust_region_tool_rows(), multiplier_rows(),
                                           trust_region_variant_rows(), first_order_rows(), off_policy_rows(),
                                           offline_rows(), budget_rows(), multi_agent_rows(), trailing_rows()}) {
      all.insert(all.end(), part.begin(), part.end());
    }
    return all;
  }();
  return rows;
}

const ConfigKeyRow& row_of(const ConfigKey& key) {
  if (const ConfigKeyRow* row = find_row(schema_rows(), key.key)) return *row;
  throw ConfigError("internal: '" + std::string(key.key) + "' is not in the schema table");
}

std::string describe_node(const YAML::Node& node) {
  if (node.IsScalar()) {
    std::string quoted(1, '\'');
    quoted += printable_excerpt(node.Scalar());
    quoted += '\'';
    return quoted;
  }
  if (node.IsNull()) return "no value";
  YAML::Emitter out;
  out << YAML::Flow << node;
  return std::string(node.IsSequence() ? "the sequence " : "the mapping ") + printable_excerpt(out.c_str());
}

std::string expected_text(const ConfigKey& key) {
  switch (key.type) {
    case ValueType::boolean: return "true or false";
    case ValueType::integer: return "an integer in " + key.range.to_string();
    case ValueType::real: return "a real number in " + key.range.to_string();
    case ValueType::text: return "a non-empty string";
    case ValueType::choice: return "one of " + key.valid_values();
    case ValueType::integer_list:
      return "a non-empty list of integers in " + key.range.to_string() + ", e.g. [64, 64]";
    case ValueType::constraint_list: return "a list of {terms, limit}";
    case ValueType::mapping: return "a mapping of parameter: value, e.g. {bombs: 12}";
  }
  return "";
}

[[noreturn]] void throw_type_error(const ConfigKey& key, const YAML::Node& value,
                                   const std::string& origin, const std::string& detail = "") {
  std::string message = origin + ": key '" + std::string(key.key) + "' expects " +
                        expected_text(key) + ", got " + describe_node(value);
  if (!detail.empty()) message += " (" + detail + ")";
  throw ConfigError(message);
}

[[noreturn]] void throw_range_error(const ConfigKey& key, const std::string& value_text,
                                    const std::string& origin) {
  throw ConfigError(origin + ": key '" + std::string(key.key) + "' = " + printable_excerpt(value_text) +
                    " is out of range; valid: " + key.range.to_string());
}

// A bool, integer or real member.
template <typename Access>
constexpr bool is_scalar_field = std::is_same_v<Access, Field<bool>> || std::is_same_v<Access, Field<int>> ||
                                 std::is_same_v<Access, Field<std::int64_t>> || std::is_same_v<Access, Field<double>>;

// A plain (unquoted) scalar: quoted text such as '5' is a string, not a number.
bool is_plain_scalar(const YAML::Node& node) { return node.IsScalar() && node.Tag() != "!"; }

// Reads a plain scalar into a bool, integer or real member through the shared
// parser (common/parameter_table.h); fails naming key, value and origin.
template <typename T>
T read_scalar(const ConfigKey& key, const YAML::Node& value, const std::string& origin) {
  if (!is_plain_scalar(value)) {
    throw_type_error(key, value, origin,
                     value.IsScalar() && !std::is_same_v<T, bool> ? "quoted text is a string" : "");
  }
  T parsed{};
  switch (parse_scalar(value.Scalar(), key.range, parsed)) {
    case ScalarProblem::none: break;
    case ScalarProblem::not_a_value: throw_type_error(key, value, origin);
    case ScalarProblem::out_of_range: throw_range_error(key, value.Scalar(), origin);
  }
  return parsed;
}

}  // namespace

std::string_view to_string(ConfigLayer layer) {
  switch (layer) {
    case ConfigLayer::run: return "run";
    case ConfigLayer::algorithm: return "algorithm";
    case ConfigLayer::environment: return "environment";
  }
  return "<invalid>";
}

std::string ConfigKey::valid_values() const {
  switch (type) {
    case ValueType::boolean: return "true | false";
    case ValueType::integer:
    case ValueType::real: return range.to_string();
    case ValueType::integer_list: return "list of " + range.to_string();
    case ValueType::constraint_list: return "list of {terms: [names] or all, limit: >= 0}";
    case ValueType::text: return "non-empty text";
    case ValueType::mapping: return "parameter: value pairs";
    case ValueType::choice: {
      std::string joined;
      for (std::string_view name : choices) {
        if (!joined.empty()) joined += " | ";
        joined += name;
      }
      return joined;
    }
  }
  return "";
}

std::string ConfigKey::used_by_text() const {
  if (used_by == kAllAlgorithms) return "all";
  std::string joined;
  for (std::size_t i = 0; i < kAlgorithmNames.size(); ++i) {
    if ((used_by & (AlgorithmSet{1} << i)) == 0) continue;
    if (!joined.empty()) joined += ", ";
    joined += kAlgorithmNames[i];
  }
  return joined;
}

const std::vector<ConfigKey>& run_config_schema() {
  static const std::vector<ConfigKey> keys = [] {
    std::vector<ConfigKey> out;
    for (const ConfigKeyRow& row : schema_rows()) out.push_back(row.info);
    return out;
  }();
  return keys;
}

std::string config_schema_markdown() {
  auto escape_bars = [](const std::string& text) {  // '|' would split a Markdown cell
    std::string out;
    for (char c : text) {
      if (c == '|') out += '\\';
      out += c;
    }
    return out;
  };
  std::ostringstream table;
  table << "| key | type | default from | valid values | algorithms | description |\n"
        << "|---|---|---|---|---|---|\n";
  for (const ConfigKey& entry : run_config_schema()) {
    table << "| `" << entry.key << "` | " << to_string(entry.type) << " | "
          << to_string(entry.default_source) << " | " << escape_bars(entry.valid_values())
          << " | " << entry.used_by_text() << " | " << entry.description << " |\n";
  }
  return table.str();
}

const ConfigKey* find_config_key(std::string_view key) {
  const ConfigKeyRow* row = find_row(schema_rows(), key);
  return row != nullptr ? &row->info : nullptr;
}

std::string config_key_list() {
  std::string joined;
  for (const ConfigKey& entry : run_config_schema()) {
    if (!joined.empty()) joined += ", ";
    joined += entry.key;
  }
  return joined;
}

std::string unknown_key_hint(std::string_view unknown) {
  if (const ForeignKeySpelling* foreign = find_foreign_key_spelling(unknown)) {
    return " (did you mean '" + std::string(foreign->key) + "'? " + std::string(foreign->spelling) + " in " +
           std::string(foreign->libraries) + ")";
  }
  const std::string closest = closest_row_key(schema_rows(), unknown);
  return closest.empty() ? std::string() : " (did you mean '" + closest + "'?)";
}

void set_config_value(RunConfig& config, const ConfigKey& key, const YAML::Node& value,
                      const std::string& origin) {
  const ConfigKeyRow& row = row_of(key);
  std::visit(
      [&](auto&& access) {
        using Access = std::decay_t<decltype(access)>;
        if constexpr (is_scalar_field<Access>) {
          using T = std::remove_cvref_t<decltype(access.in(config))>;
          access.in(config) = read_scalar<T>(key, value, origin);
        } else if constexpr (std::is_same_v<Access, Field<std::string>>) {
          if (!value.IsScalar() || value.Scalar().empty()) throw_type_error(key, value, origin);
          access.in(config) = value.Scalar();
        } else if constexpr (std::is_same_v<Access, Field<TextPairs>>) {
          // Merged into the pairs so far: a later layer changes single keys
          // (the environment checks keys and values when it is built).
          if (value.IsNull()) return;
          if (!value.IsMap()) throw_type_error(key, value, origin);
          for (const auto& pair : value) {
            if (!pair.first.IsScalar() || !pair.second.IsScalar()) throw_type_error(key, value, origin);
            TextPairs& pairs = access.in(config);
            const std::string name = pair.first.Scalar();
            const auto same = std::find_if(pairs.begin(), pairs.end(),
                                           [&](const auto& p) { return p.first == name; });
            if (same != pairs.end()) {
              same->second = pair.second.Scalar();
            } else {
              pairs.emplace_back(name, pair.second.Scalar());
            }
          }
        } else if constexpr (std::is_same_v<Access, Field<std::vector<int>>>) {
          if (!value.IsSequence() || value.size() == 0) throw_type_error(key, value, origin);
          std::vector<int> list;
          for (const YAML::Node& element : value) {
            int parsed = 0;
            const ScalarProblem problem = is_plain_scalar(element) ? parse_scalar(element.Scalar(), key.range, parsed)
                                                                   : ScalarProblem::not_a_value;
            if (problem == ScalarProblem::not_a_value) throw_type_error(key, value, origin);
            if (problem == ScalarProblem::out_of_range) {
              throw_range_error(key, describe_node(value) + " (element " + printable_excerpt(element.Scalar()) + ")",
                                origin);
            }
            list.push_back(parsed);
          }
          access.in(config) = std::move(list);
        } else if constexpr (std::is_same_v<Access, Field<std::vector<ConstraintConfig>>>) {
          access.in(config) = parse_constraint_list(value, origin, kMaxConstraintCount);
        } else {  // EnumAccess
          if (!value.IsScalar()) throw_type_error(key, value, origin);
          const auto found = std::find(key.choices.begin(), key.choices.end(), value.Scalar());
          if (found == key.choices.end()) {
            throw ConfigError(origin + ": key '" + std::string(key.key) + "' = '" +
                              printable_excerpt(value.Scalar()) + "' is not valid; valid values: " +
                              key.valid_values());
          }
          access.set(config, static_cast<int>(found - key.choices.begin()));
        }
      },
      row.field);
}

std::string config_value_to_yaml(const RunConfig& config, const ConfigKey& key) {
  const ConfigKeyRow& row = row_of(key);
  return std::visit(
      [&](auto&& access) -> std::string {
        using Access = std::decay_t<decltype(access)>;
        if constexpr (is_scalar_field<Access>) {
          return scalar_text(access.in_const(config));
        } else if constexpr (std::is_same_v<Access, Field<std::string>>) {
          YAML::Emitter out;  // quotes the text where YAML would misread it
          out << access.in_const(config);
          return out.c_str();
        } else if constexpr (std::is_same_v<Access, Field<std::vector<int>>>) {
          std::ostringstream out;
          out << "[";
          for (std::size_t i = 0; i < access.in_const(config).size(); ++i) {
            out << (i ? ", " : "") << access.in_const(config)[i];
          }
          out << "]";
          return out.str();
        } else if constexpr (std::is_same_v<Access, Field<std::vector<ConstraintConfig>>>) {
          return constraint_list_to_yaml(access.in_const(config));
        } else if constexpr (std::is_same_v<Access, Field<TextPairs>>) {
          YAML::Emitter out;  // quotes the text where YAML would misread it
          out << YAML::Flow << YAML::BeginMap;
          for (const auto& [name, text] : access.in_const(config)) out << YAML::Key << name << YAML::Value << text;
          out << YAML::EndMap;
          return out.c_str();
        } else {  // EnumAccess
          const int index = access.get(config);
          return std::string(key.choices[static_cast<std::size_t>(index)]);
        }
      },
      row.field);
}

}  // namespace bsg
