// The rows of TrustRegionKeys (common/trust_region_keys.h) in the key table:
// the tools, between the returns' rows and the multipliers', and the
// variants' switches, after the multipliers' rows. A trust-region variant's
// own key is a member of TrustRegionKeys and a row of trust_region_variant_rows
// applying to algorithm_bit(Algorithm::<its name>).
#include "common/trust_region_keys.h"

#include <vector>

#include "common/config_key_rows.h"

namespace bsg {

std::string_view to_string(CpoRSign sign) { return key_rows::enum_name(kCpoRSignNames, sign); }
std::string_view to_string(PcpoProjection projection) {
  return key_rows::enum_name(kPcpoProjectionNames, projection);
}

namespace key_rows {

namespace {
// The line search's keys: RCPO takes the natural-gradient step without one (OmniSafe's NaturalPG).
constexpr AlgorithmSet kLineSearching = kTrustRegion & ~algorithm_bit(Algorithm::rcpo);
// MACPO's agents take CPO's step (algos/multi_agent/macpo_update.h) with its tools and switches.
constexpr AlgorithmSet kMacpo = algorithm_bit(Algorithm::macpo);
}  // namespace

// clang-format off
std::vector<ConfigKeyRow> trust_region_tool_rows() {
  using L = ConfigLayer;
  using R = RunConfig;
  using N = NumericRange;
  using K = TrustRegionKeys;
  return {
    // --- trust region (docs/algorithms.md#trust-region-tools) ---
    real("target_kl", field<&R::trust_region, &K::target_kl>(), L::algorithm, N::above(0), kOnPolicy | kMacpo,
         "delta: trust-region size (mean KL per action dimension, Q8); first-order algorithms: the "
         "early-stop KL (per sample summed over action dimensions, averaged over samples)"),
    real("cg_damping", field<&R::trust_region, &K::cg_damping>(), L::algorithm, N::at_least(0), kTrustRegion | kMacpo,
         "damping added to the Fisher-vector product"),
    integer("cg_iters", field<&R::trust_region, &K::cg_iters>(), L::algorithm, N::closed(1, 1000), kTrustRegion | kMacpo,
            "conjugate-gradient iterations"),
    integer("fvp_subsample", field<&R::trust_region, &K::fvp_subsample>(), L::algorithm, N::closed(1, 1000), kTrustRegion | kMacpo,
            "the Fisher-vector product uses every k-th observation of the batch"),
    integer("backtrack_budget", field<&R::trust_region, &K::backtrack_budget>(), L::algorithm, N::closed(1, 1000), kLineSearching | kMacpo,
            "Q11: line-search steps (original: 15, CPO 20; report: CPO and PCPO 25)"),
    real("backtrack_decay", field<&R::trust_region, &K::backtrack_decay>(), L::algorithm, N::open(0, 1), kLineSearching | kMacpo,
         "line-search step shrink factor"),
    real("kl_accept_factor", field<&R::trust_region, &K::kl_accept_factor>(), L::algorithm, N::above(0), kLineSearching | kMacpo,
         "Q13: the line search accepts a step with KL <= kl_accept_factor * target_kl"),
  };
}

std::vector<ConfigKeyRow> trust_region_variant_rows() {
  using L = ConfigLayer;
  using R = RunConfig;
  using N = NumericRange;
  using K = TrustRegionKeys;
  return {
    // --- algorithm switches (docs/algorithms.md#pdo, #cpo, #pcpo) ---
    choice("cpo_r_sign", enum_access<&R::trust_region, &K::cpo_r_sign>(), kCpoRSignNames, L::algorithm,
           algorithm_bit(Algorithm::cpo) | kMacpo,
           "Q10: sign of r in CPO's dual: original (as the code) or corrected"),
    boolean("cpo_clamp_a", field<&R::trust_region, &K::cpo_clamp_a>(), L::algorithm, algorithm_bit(Algorithm::cpo) | kMacpo,
            "clamp CPO's A = q - r^2/s at 0 when rounding makes it negative (else an error)"),
    choice("pcpo_projection", enum_access<&R::trust_region, &K::pcpo_projection>(), kPcpoProjectionNames,
           L::algorithm, algorithm_bit(Algorithm::pcpo),
           "metric of PCPO's projection: kl (Fisher) or l2"),
    boolean("pcpo_line_search", field<&R::trust_region, &K::pcpo_line_search>(), L::algorithm,
            algorithm_bit(Algorithm::pcpo),
            "run the constrained line search on PCPO's step (false: apply it directly)"),
    boolean("pdo_line_search", field<&R::trust_region, &K::pdo_line_search>(), L::algorithm, algorithm_bit(Algorithm::pdo),
            "Q14: run the TRPO line search on PDO's reward loss (original); false: apply step"),
    real("crpo_tolerance", field<&R::trust_region, &K::crpo_tolerance>(), L::algorithm, N::at_least(0), algorithm_bit(Algorithm::crpo),
         "CRPO's eta (OmniSafe's distance): the step minimises a constraint's cost once J_C > d + eta"),
  };
}
// clang-format on

}  // namespace key_rows
}  // namespace bsg
