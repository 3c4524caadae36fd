// A trained run's policy, read from its run directory's latest checkpoint, as an acting policy
// (algos/core/acting_policy.h) of whichever family trained it: the one loader behind `bsg eval`,
// `bsg collect` and anything later. The checkpoint's own numbers are used as they are: an
// on-policy policy normalises observations with the frozen statistics and samples at the sigma
// of the checkpoint's last epoch.
#pragma once

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <string_view>

#include "algos/core/acting_policy.h"
#include "algos/training/run_directory.h"
#include "common/run_config.h"

namespace bsg::algos {

// How a policy standardises a raw observation s before its network (bsg.load_policy shows it):
// s_hat = (s - mean) / (std + std_epsilon), then clipped to [-clip, clip] if clip > 0.
struct ObservationStandardization {
  Eigen::VectorXd mean;
  Eigen::VectorXd std;
  double std_epsilon = 0.0;
  double clip = 0.0;
};

class LoadedPolicy : public ActingPolicy {
 public:
  const RunConfig& config() const { return config_; }
  int epochs_completed() const { return epochs_completed_; }
  // The sigma of sampled Gaussian actions (on-policy), 0 for the off-policy actors.
  virtual double sampled_action_std() const = 0;
  // How the family calls the actions of `mode` ("mean actions" / "deterministic actions", ...).
  virtual std::string_view action_words(ActionMode mode) const = 0;
  // The frozen statistics the policy acts with; nullopt when it sees raw observations (the
  // off-policy learners, an on-policy run without use_standardized_obs).
  virtual std::optional<ObservationStandardization> observation_standardization() const = 0;

 protected:
  LoadedPolicy(RunConfig config, int epochs_completed)
      : config_(std::move(config)), epochs_completed_(epochs_completed) {}

 private:
  RunConfig config_;
  int epochs_completed_;
};

// Throws naming the directory or file at fault (not a run directory, corrupt checkpoint).
std::unique_ptr<LoadedPolicy> load_policy(const RunDirectory& directory);

}  // namespace bsg::algos
