#include "algos/training/progress_line.h"

#include <cmath>
#include <cstdio>

namespace bsg::algos {

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const long long total = std::llround(seconds);
  char text[48];
  if (total < 60) {
    std::snprintf(text, sizeof(text), "%llds", total);
  } else if (total < 3600) {
    std::snprintf(text, sizeof(text), "%lldm%02llds", total / 60, total % 60);
  } else if (total < 86400) {
    std::snprintf(text, sizeof(text), "%lldh%02lldm", total / 3600, (total % 3600) / 60);
  } else {
    std::snprintf(text, sizeof(text), "%lldd%02lldh", total / 86400, (total % 86400) / 3600);
  }
  return text;
}

std::string format_progress_line(const ProgressLineInputs& in) {
  char text[256];
  int n = std::snprintf(text, sizeof(text), "epoch %4d/%d  return %8.2f  cost %7.2f", in.epoch + 1, in.epochs,
                        in.mean_return, in.mean_cost);
  std::string line(text, static_cast<std::size_t>(n));
  if (in.cost_limit) {
    n = std::snprintf(text, sizeof(text), " (limit %g)", *in.cost_limit);
    line.append(text, static_cast<std::size_t>(n));
  }
  if (in.lagrange_multiplier) {
    n = std::snprintf(text, sizeof(text), "  lambda %.4f", *in.lagrange_multiplier);
    line.append(text, static_cast<std::size_t>(n));
  }
  if (!std::isnan(in.kl)) {  // the off-policy learners have no KL to show
    n = std::snprintf(text, sizeof(text), "  KL %.5f", in.kl);
    line.append(text, static_cast<std::size_t>(n));
  }
  n = std::snprintf(text, sizeof(text), "  %.2f s/epoch  ETA %s", in.epoch_seconds,
                    in.eta_seconds ? format_duration(*in.eta_seconds).c_str() : "once learning starts");
  line.append(text, static_cast<std::size_t>(n));
  return line;
}

}  // namespace bsg::algos
