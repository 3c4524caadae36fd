#include "common/learner_preset.h"

namespace bsg {

const std::vector<std::pair<std::string_view, std::string_view>>& corrected_learner_settings() {
  static const std::vector<std::pair<std::string_view, std::string_view>> settings = {
      {"zero_bias_init", "true"},               // Q1: the report's zero biases
      {"exact_parallel_variance", "true"},      // Q4: Chan's exact merge
      {"consistent_return_statistic", "true"},  // Q5: the statistic in raw units throughout
      {"cpo_r_sign", "corrected"},              // Q10: CPO's dual with the right sign of r
      {"rescale_value_output", "true"},         // Q19: V's predictions kept when the statistic changes
      {"value_time_input", "true"},             // Q20: V and V_C see the time left in the episode
  };
  return settings;
}

}  // namespace bsg
