#include "common/run_config.h"

#include "common/config_key_rows.h"

namespace bsg {

std::string_view to_string(Algorithm alg) { return key_rows::enum_name(kAlgorithmNames, alg); }
std::string_view to_string(Learner learner) { return key_rows::enum_name(kLearnerNames, learner); }

}  // namespace bsg
