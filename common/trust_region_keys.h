// TrustRegionKeys: the configuration keys of the trust-region family (trpo,
// lag-trpo, cpo, pdo, pcpo, crpo; docs/algorithms.md#trust-region-tools): the
// tools its updates share (the trust-region size, conjugate gradient, the
// Fisher-vector product, the line search) and each variant's own switches.
// RunConfig holds them as `trust_region`; their rows in the key table (type,
// range, algorithms, description) are in trust_region_keys.cpp.
//
// Parameters (the member initialisers; a run takes its algorithm's from
// configs/algorithms/<alg>.yaml, see the rows for which algorithms a key applies to):
//   target_kl = 0.01          delta (first-order updates: the early-stop KL)
//   cg_damping = 0.1, cg_iters = 10, fvp_subsample = 4
//   backtrack_budget = 15 (Q11), backtrack_decay = 0.8, kl_accept_factor = 1.5 (Q13)
//   cpo_r_sign = original (Q10), cpo_clamp_a = false               cpo
//   pcpo_projection = kl, pcpo_line_search = true                   pcpo
//   pdo_line_search = true (Q14)                                    pdo
//   crpo_tolerance = 2.0                                            crpo
#pragma once

#include <array>
#include <string_view>

namespace bsg {

// Sign of r in CPO's dual solution (docs/algorithms.md#cpo, quirk Q10).
enum class CpoRSign { original, corrected };
inline constexpr std::array<std::string_view, 2> kCpoRSignNames = {"original", "corrected"};

// Metric of PCPO's projection step (docs/algorithms.md#pcpo): Fisher (KL) or Euclidean (L2).
enum class PcpoProjection { kl, l2 };
inline constexpr std::array<std::string_view, 2> kPcpoProjectionNames = {"kl", "l2"};

std::string_view to_string(CpoRSign sign);
std::string_view to_string(PcpoProjection projection);

struct TrustRegionKeys {
  // --- the tools (docs/algorithms.md#trust-region-tools) ---
  double target_kl = 0.01;         // delta; also the first-order updates' early-stop KL
  double cg_damping = 0.1;
  int cg_iters = 10;
  int fvp_subsample = 4;           // FVP uses every k-th observation
  int backtrack_budget = 15;       // Q11
  double backtrack_decay = 0.8;
  double kl_accept_factor = 1.5;   // Q13

  // --- the variants' own switches ---
  CpoRSign cpo_r_sign = CpoRSign::original;  // Q10
  bool cpo_clamp_a = false;                  // docs/algorithms.md#cpo degenerate A < 0
  PcpoProjection pcpo_projection = PcpoProjection::kl;
  bool pcpo_line_search = true;
  bool pdo_line_search = true;               // Q14
  double crpo_tolerance = 2.0;               // CRPO's eta: a cost step once J_C > d + eta

  bool operator==(const TrustRegionKeys&) const = default;
};

}  // namespace bsg
