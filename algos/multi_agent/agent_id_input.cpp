#include "algos/multi_agent/agent_id_input.h"

#include <stdexcept>
#include <string>

namespace bsg::algos {
namespace {

void check_agent(int agent, int width) {
  if (width > 0 && (agent < 0 || agent >= width)) {
    throw std::invalid_argument("agent id " + std::to_string(agent) + " outside [0, " + std::to_string(width) + ")");
  }
}

}  // namespace

int agent_id_width(bool shared, int agent_count) { return shared ? agent_count : 0; }

void write_agent_input(const Eigen::Ref<const Eigen::VectorXd>& x, int agent, int width,
                       Eigen::Ref<Eigen::VectorXd> input) {
  check_agent(agent, width);
  if (input.size() != x.size() + width) {
    throw std::invalid_argument("agent input of " + std::to_string(input.size()) + " entries for " +
                                std::to_string(x.size()) + " inputs and an id of " + std::to_string(width));
  }
  input.head(x.size()) = x;
  if (width == 0) return;
  input.tail(width).setZero();
  input[x.size() + agent] = 1.0;
}

void write_agent_inputs(const Eigen::Ref<const Eigen::MatrixXd>& xs, int agent, int width,
                        Eigen::Ref<Eigen::MatrixXd> inputs) {
  check_agent(agent, width);
  if (inputs.cols() != xs.cols() + width || inputs.rows() != xs.rows()) {
    throw std::invalid_argument("agent inputs of " + std::to_string(inputs.rows()) + " x " +
                                std::to_string(inputs.cols()) + " for " + std::to_string(xs.rows()) + " x " +
                                std::to_string(xs.cols()) + " inputs and an id of " + std::to_string(width));
  }
  inputs.leftCols(xs.cols()) = xs;
  if (width == 0) return;
  inputs.rightCols(width).setZero();
  inputs.col(xs.cols() + agent).setOnes();
}

}  // namespace bsg::algos
