// The rows of the key table (run_config_schema.h) as the files that write them
// see them: run_config_schema.cpp (the keys of RunConfig itself) and each
// group's file (trust_region_keys.cpp, multiplier_keys.cpp, first_order_keys.cpp,
// off_policy_keys.cpp). A row is a ConfigKey and the way to its member of
// RunConfig, a member of RunConfig itself (field<&RunConfig::gamma>()) or of one
// of its groups (field<&RunConfig::trust_region, &TrustRegionKeys::cg_iters>()).
// run_config_schema.cpp puts the groups' rows together in one fixed order: the
// order of config.yaml, `bsg train --print-config` and configs/README.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "common/algorithms.h"
#include "common/constraint_config.h"
#include "common/parameter_table.h"
#include "common/run_config.h"
#include "common/run_config_schema.h"

namespace bsg::key_rows {

inline constexpr double kIntMax = 2147483647.0;

// The member a path of member pointers leads to: config.*First, then .*Rest...
template <auto First, auto... Rest, typename Object>
constexpr auto& member_at(Object& object) {
  if constexpr (sizeof...(Rest) == 0) {
    return object.*First;
  } else {
    return member_at<Rest...>(object.*First);
  }
}

// Read and write access to one member of RunConfig of type T.
template <typename T>
struct Field {
  T& (*in)(RunConfig&);
  const T& (*in_const)(const RunConfig&);
};

template <auto... Path>
auto field() {
  using T = std::remove_cvref_t<decltype(member_at<Path...>(std::declval<RunConfig&>()))>;
  return Field<T>{[](RunConfig& config) -> T& { return member_at<Path...>(config); },
                  [](const RunConfig& config) -> const T& { return member_at<Path...>(config); }};
}

// Access to an enum member through its underlying index into its names.
struct EnumAccess {
  int (*get)(const RunConfig&);
  void (*set)(RunConfig&, int);
};

template <auto... Path>
EnumAccess enum_access() {
  return {[](const RunConfig& config) { return static_cast<int>(member_at<Path...>(config)); },
          [](RunConfig& config, int index) {
            auto& member = member_at<Path...>(config);
            member = static_cast<std::remove_cvref_t<decltype(member)>>(index);
          }};
}

using TextPairs = std::vector<std::pair<std::string, std::string>>;
using FieldAccess = std::variant<Field<bool>, Field<int>, Field<std::int64_t>, Field<double>,
                                 Field<std::string>, Field<std::vector<int>>,
                                 Field<std::vector<ConstraintConfig>>, Field<TextPairs>, EnumAccess>;

struct ConfigKeyRow {
  ConfigKey info;
  FieldAccess field;
};

// The algorithm families the keys apply to, read off the table of algorithms (common/algorithms.h).
constexpr AlgorithmSet algorithms_where(bool AlgorithmInfo::*property) {
  AlgorithmSet set = 0;
  for (const AlgorithmInfo& info : kAlgorithms) {
    if (info.*property) set |= algorithm_bit(info.alg);
  }
  return set;
}
constexpr AlgorithmSet algorithms_in(AlgorithmFamily family) {
  AlgorithmSet set = 0;
  for (const AlgorithmInfo& info : kAlgorithms) {
    if (info.family == family) set |= algorithm_bit(info.alg);
  }
  return set;
}
inline constexpr AlgorithmSet kLagrangian = algorithms_where(&AlgorithmInfo::lagrange_multiplier);
inline constexpr AlgorithmSet kTrustRegion = algorithms_in(AlgorithmFamily::trust_region);
inline constexpr AlgorithmSet kFirstOrder = algorithms_in(AlgorithmFamily::first_order);
inline constexpr AlgorithmSet kOffPolicy = algorithms_in(AlgorithmFamily::off_policy);
inline constexpr AlgorithmSet kOffline = algorithms_in(AlgorithmFamily::offline);
inline constexpr AlgorithmSet kMultiAgent = algorithms_in(AlgorithmFamily::multi_agent);
inline constexpr AlgorithmSet kOnPolicy = kTrustRegion | kFirstOrder;
// The multi-agent learners whose actors take PPO's Adam steps (MACPO's take CPO's step).
inline constexpr AlgorithmSet kMultiAgentFirstOrder = kMultiAgent & ~algorithm_bit(Algorithm::macpo);

// Row builders, one per value type.
inline ConfigKeyRow boolean(std::string_view key, Field<bool> member, ConfigLayer layer, AlgorithmSet used_by,
                            std::string_view description) {
  return {{key, ValueType::boolean, layer, {}, {}, used_by, description}, member};
}
template <typename Int>
ConfigKeyRow integer(std::string_view key, Field<Int> member, ConfigLayer layer, NumericRange range,
                     AlgorithmSet used_by, std::string_view description) {
  return {{key, ValueType::integer, layer, range, {}, used_by, description}, member};
}
inline ConfigKeyRow real(std::string_view key, Field<double> member, ConfigLayer layer, NumericRange range,
                         AlgorithmSet used_by, std::string_view description) {
  return {{key, ValueType::real, layer, range, {}, used_by, description}, member};
}
inline ConfigKeyRow text(std::string_view key, Field<std::string> member, ConfigLayer layer,
                         std::string_view description, AlgorithmSet used_by = kAllAlgorithms) {
  return {{key, ValueType::text, layer, {}, {}, used_by, description}, member};
}
inline ConfigKeyRow choice(std::string_view key, EnumAccess access, std::span<const std::string_view> names,
                           ConfigLayer layer, AlgorithmSet used_by, std::string_view description) {
  return {{key, ValueType::choice, layer, {}, names, used_by, description}, access};
}
inline ConfigKeyRow constraint_list(std::string_view key, Field<std::vector<ConstraintConfig>> member,
                                    AlgorithmSet used_by, std::string_view description) {
  return {{key, ValueType::constraint_list, ConfigLayer::run, {}, {}, used_by, description}, member};
}
inline ConfigKeyRow integer_list(std::string_view key, Field<std::vector<int>> member, ConfigLayer layer,
                                 NumericRange element_range, AlgorithmSet used_by, std::string_view description) {
  return {{key, ValueType::integer_list, layer, element_range, {}, used_by, description}, member};
}
inline ConfigKeyRow mapping(std::string_view key, Field<TextPairs> member, ConfigLayer layer, AlgorithmSet used_by,
                            std::string_view description) {
  return {{key, ValueType::mapping, layer, {}, {}, used_by, description}, member};
}

// An enum value's spelling in its names, "<invalid>" past their end.
template <std::size_t N, typename Enum>
std::string_view enum_name(const std::array<std::string_view, N>& names, Enum value) {
  const auto index = static_cast<std::size_t>(value);
  return index < N ? names[index] : std::string_view("<invalid>");
}

// The groups' rows, each in its file and in the table's order. The trust-region
// family's rows come in two parts: its tools, before the multipliers' rows, and
// its variants' switches, after them.
std::vector<ConfigKeyRow> trust_region_tool_rows();     // trust_region_keys.cpp
std::vector<ConfigKeyRow> multiplier_rows();            // multiplier_keys.cpp
std::vector<ConfigKeyRow> trust_region_variant_rows();  // trust_region_keys.cpp
std::vector<ConfigKeyRow> first_order_rows();           // first_order_keys.cpp
std::vector<ConfigKeyRow> off_policy_rows();            // off_policy_keys.cpp
std::vector<ConfigKeyRow> offline_rows();               // offline_keys.cpp
std::vector<ConfigKeyRow> budget_rows();                // budget_keys.cpp
std::vector<ConfigKeyRow> multi_agent_rows();           // multi_agent_keys.cpp

}  // namespace bsg::key_rows
