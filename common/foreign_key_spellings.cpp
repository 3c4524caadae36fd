#include "common/foreign_key_spellings.h"

#include <array>

namespace bsg {
namespace {

// Only names whose meaning is bsg's key's (tau: target <- (1 - tau) target + tau online, as
// polyak here; Spinning Up's own polyak is 1 - tau and is not listed, being bsg's name).
constexpr std::array kSpellings{
    ForeignKeySpelling{"tau", "polyak", "Stable-Baselines3, CleanRL and Tianshou"},
    ForeignKeySpelling{"q_lr", "critic_lr", "CleanRL"},
    ForeignKeySpelling{"policy_lr", "actor_lr", "CleanRL"},
    ForeignKeySpelling{"pi_lr", "actor_lr", "Spinning Up"},
    ForeignKeySpelling{"gae_lambda", "lam", "Stable-Baselines3, CleanRL and Tianshou"},
    ForeignKeySpelling{"clip_coef", "clip", "CleanRL"},
    ForeignKeySpelling{"clip_range", "clip", "Stable-Baselines3"},
    ForeignKeySpelling{"clip_ratio", "clip", "Spinning Up"},
    ForeignKeySpelling{"eps_clip", "clip", "Tianshou"},
    ForeignKeySpelling{"update_epochs", "update_iters", "CleanRL"},
    ForeignKeySpelling{"n_epochs", "update_iters", "Stable-Baselines3"},
    ForeignKeySpelling{"train_pi_iters", "update_iters", "Spinning Up"},
    ForeignKeySpelling{"repeat_per_collect", "update_iters", "Tianshou"},
    ForeignKeySpelling{"train_v_iters", "train_v_iterations", "Spinning Up"},
    ForeignKeySpelling{"learning_starts", "start_steps", "Stable-Baselines3 and CleanRL"},
    ForeignKeySpelling{"replay_size", "buffer_size", "Spinning Up"},
    ForeignKeySpelling{"train_freq", "update_every", "Stable-Baselines3"},
    ForeignKeySpelling{"policy_frequency", "policy_delay", "CleanRL"},
    ForeignKeySpelling{"target_policy_noise", "policy_noise", "Stable-Baselines3"},
    ForeignKeySpelling{"target_noise", "policy_noise", "Spinning Up"},
    ForeignKeySpelling{"act_noise", "exploration_noise", "Spinning Up"},
    ForeignKeySpelling{"alpha", "alpha_init", "CleanRL and Spinning Up"},
    ForeignKeySpelling{"ent_coef", "alpha_init", "Stable-Baselines3"},
    ForeignKeySpelling{"autotune", "auto_alpha", "CleanRL"},
};

}  // namespace

std::span<const ForeignKeySpelling> foreign_key_spellings() { return kSpellings; }

const ForeignKeySpelling* find_foreign_key_spelling(std::string_view spelling) {
  for (const ForeignKeySpelling& row : kSpellings) {
    if (row.spelling == spelling) return &row;
  }
  return nullptr;
}

}  // namespace bsg
