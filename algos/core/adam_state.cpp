#include "algos/core/adam_state.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace bsg::algos {
namespace {

// A step count saved as a double: a non-negative integer below 2^53, where doubles stop counting.
long long step_count_of(const NamedScalar& entry) {
  const double t = entry.value;
  if (!(t >= 0.0) || t != std::floor(t) || t > 9e15) {
    throw std::invalid_argument("Adam state: " + entry.name + " = " + std::to_string(t) +
                                " must be a non-negative integer step count");
  }
  return static_cast<long long>(t);
}

void expect_name(const NamedScalar& entry, const std::string& expected) {
  if (entry.name != expected) {
    throw std::invalid_argument("Adam state: entry '" + entry.name + "' where '" + expected + "' was expected");
  }
}

std::string name(std::string_view prefix, std::string_view field) { return std::string(prefix) + std::string(field); }
std::string indexed(std::string_view prefix, std::string_view field, Eigen::Index i) {
  return name(prefix, field) + "/" + std::to_string(i);
}

}  // namespace

void save_adam_state(const Adam& adam, BinaryWriter& writer) {
  writer.write_vector(adam.first_moment());
  writer.write_vector(adam.second_moment());
  writer.write_i64(adam.step_count());
}

void load_adam_state(Adam& adam, BinaryReader& reader, const std::string& owner) {
  const Eigen::VectorXd first = reader.read_vector(owner + " Adam first moment", adam.num_parameters());
  const Eigen::VectorXd second = reader.read_vector(owner + " Adam second moment", adam.num_parameters());
  const std::int64_t steps = reader.read_i64(owner + " Adam step count");
  if (steps < 0) reader.fail(owner + " Adam step count is negative");
  adam.set_state(first, second, steps);
}

std::vector<NamedScalar> adam_state_entries(const Adam& adam, std::string_view prefix, AdamEntryLayout layout) {
  const auto t = static_cast<double>(adam.step_count());
  if (layout == AdamEntryLayout::moments_then_step) {
    if (adam.num_parameters() != 1) {
      throw std::invalid_argument("Adam state: the moments-then-step entries hold one parameter, this Adam has " +
                                  std::to_string(adam.num_parameters()));
    }
    return {{name(prefix, "m"), adam.first_moment()[0]}, {name(prefix, "v"), adam.second_moment()[0]},
            {name(prefix, "t"), t}};
  }
  std::vector<NamedScalar> entries{{name(prefix, "t"), t}};
  if (adam.step_count() == 0) return entries;
  const Eigen::Index p = adam.num_parameters();
  entries.reserve(static_cast<std::size_t>(1 + 2 * p));
  for (Eigen::Index i = 0; i < p; ++i) entries.push_back({indexed(prefix, "m", i), adam.first_moment()[i]});
  for (Eigen::Index i = 0; i < p; ++i) entries.push_back({indexed(prefix, "v", i), adam.second_moment()[i]});
  return entries;
}

Eigen::Index saved_adam_parameters(std::span<const NamedScalar> saved, std::string_view prefix) {
  if (saved.empty()) throw std::invalid_argument("Adam state: no entries, '" + name(prefix, "t") + "' was expected");
  expect_name(saved.front(), name(prefix, "t"));
  const long long t = step_count_of(saved.front());
  if (t == 0) {
    if (saved.size() != 1) throw std::invalid_argument("Adam state: moments saved before any step");
    return 0;
  }
  if (saved.size() < 3 || (saved.size() - 1) % 2 != 0) {
    throw std::invalid_argument("Adam state: " + std::to_string(saved.size() - 1) +
                                " moment entries, expected two per parameter");
  }
  return static_cast<Eigen::Index>((saved.size() - 1) / 2);
}

void restore_adam_state_entries(Adam& adam, std::span<const NamedScalar> saved, std::string_view prefix,
                                AdamEntryLayout layout) {
  const Eigen::Index p = adam.num_parameters();
  Eigen::VectorXd first = Eigen::VectorXd::Zero(p);
  Eigen::VectorXd second = Eigen::VectorXd::Zero(p);
  long long t = 0;
  if (layout == AdamEntryLayout::moments_then_step) {
    if (saved.size() != 3 || p != 1) {
      throw std::invalid_argument("Adam state: " + std::to_string(saved.size()) + " entries for " +
                                  std::to_string(p) + " parameters, expected 3 for 1");
    }
    expect_name(saved[0], name(prefix, "m"));
    expect_name(saved[1], name(prefix, "v"));
    expect_name(saved[2], name(prefix, "t"));
    t = step_count_of(saved[2]);
    first[0] = saved[0].value;
    second[0] = saved[1].value;
  } else {
    const Eigen::Index held = saved_adam_parameters(saved, prefix);
    t = step_count_of(saved.front());
    if (held != 0 && held != p) {
      throw std::invalid_argument("Adam state: moments of " + std::to_string(held) + " parameters, this Adam has " +
                                  std::to_string(p));
    }
    for (Eigen::Index i = 0; i < held; ++i) {
      const NamedScalar& m = saved[static_cast<std::size_t>(1 + i)];
      const NamedScalar& v = saved[static_cast<std::size_t>(1 + held + i)];
      expect_name(m, indexed(prefix, "m", i));
      expect_name(v, indexed(prefix, "v", i));
      first[i] = m.value;
      second[i] = v.value;
    }
  }
  adam.set_state(first, second, t);
}

}  // namespace bsg::algos
