#include "algos/offline/collection_policy.h"

#include <stdexcept>

#include "common/random.h"

namespace bsg::algos {
namespace {

class RandomPolicy final : public CollectionPolicy {
 public:
  RandomPolicy(int action_dim, double low, double high) : action_dim_(action_dim), low_(low), high_(high) {}
  std::string description() const override { return "random"; }
  void start_episode(std::uint64_t seed) override { rng_ = Rng(seed); }
  void act(std::span<const double>, std::span<double> action) override {
    if (static_cast<int>(action.size()) != action_dim_) {
      throw std::invalid_argument("random policy: asked for " + std::to_string(action.size()) +
                                  " actions, made for " + std::to_string(action_dim_));
    }
    for (double& a : action) a = uniform(rng_, low_, high_);
  }

 private:
  int action_dim_;
  double low_;
  double high_;
  Rng rng_{0};
};

}  // namespace

std::unique_ptr<CollectionPolicy> make_random_policy(int action_dim, double low, double high) {
  if (action_dim <= 0 || !(low < high)) {
    throw std::invalid_argument("random policy: needs a positive action size and low < high");
  }
  return std::make_unique<RandomPolicy>(action_dim, low, high);
}

}  // namespace bsg::algos
