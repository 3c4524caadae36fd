// The `bsg` program's subcommands. Each one registers itself on the top-level
// app and, when it is the one chosen, stores its action in `run`; main() calls
// that action after parsing so that every error is reported the same way.
#pragma once

#include <functional>

namespace CLI {
class App;
}

namespace bsg::cli {

// Returns the process exit code.
using Action = std::function<int()>;

// bsg train CONFIG [--set k=v]... [--out DIR] | --print-config | --resume DIR (cmd_train.cpp)
void add_train_command(CLI::App& app, Action& run);
// bsg eval DIR [--episodes N] [--json] (cmd_eval.cpp)
void add_eval_command(CLI::App& app, Action& run);
// bsg sweep GRID [--jobs N] [--ranks-per-run K] [--out DIR] [--dry-run] (cmd_sweep.cpp)
void add_sweep_command(CLI::App& app, Action& run);
// bsg table SWEEP_DIR [--score mean|mean_minus_std] (cmd_table.cpp)
void add_table_command(CLI::App& app, Action& run);

// bsg envs [--json] (cmd_envs.cpp)
void add_envs_command(CLI::App& app, Action& run);
// bsg rollout --env ID [--policy random|zero] [--episodes N] [--seed S] [--json] (cmd_rollout.cpp)
void add_rollout_command(CLI::App& app, Action& run);
// bsg bench [--env ID] [--steps N] [--json] (cmd_bench.cpp)
void add_bench_command(CLI::App& app, Action& run);

// bsg collect --out FILE --policy random|RUN_DIR[=SHARE]... (--episodes N | --transitions N) (cmd_collect.cpp)
void add_collect_command(CLI::App& app, Action& run);
// bsg dataset info FILE [--plot FILE.png] [--json] | bc FILE ... (cmd_dataset.cpp) | make RECIPE ...
void add_dataset_command(CLI::App& app, Action& run);
// bsg dataset make RECIPE [--out DIR] [--jobs N] (cmd_dataset_make.cpp), a subcommand of `dataset`
void add_dataset_make_command(CLI::App& dataset, Action& run);

}  // namespace bsg::cli
