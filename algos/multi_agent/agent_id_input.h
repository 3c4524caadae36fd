// The agent's one-hot id appended to a network's input when several agents share the network
// (share_policy; MAPPO's parameter sharing, Yu et al. 2022, section 4): agent i of n sees
// [x, e_i], where e_i has n entries, a 1 at position i and 0 elsewhere. Without sharing the input
// is x alone (agent_id_width = 0).
#pragma once

#include <Eigen/Core>

namespace bsg::algos {

// The entries the id adds: n when shared, 0 otherwise.
int agent_id_width(bool shared, int agent_count);

// Writes [x, e_agent] into `input` (size x.size() + width); width 0 copies x. Throws
// std::invalid_argument on a size mismatch or an agent outside [0, width).
void write_agent_input(const Eigen::Ref<const Eigen::VectorXd>& x, int agent, int width,
                       Eigen::Ref<Eigen::VectorXd> input);

// Row-wise: every row of `inputs` becomes [row of xs, e_agent].
void write_agent_inputs(const Eigen::Ref<const Eigen::MatrixXd>& xs, int agent, int width,
                        Eigen::Ref<Eigen::MatrixXd> inputs);

}  // namespace bsg::algos
