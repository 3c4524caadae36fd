// Entry point of `bsg`: parses the command line with CLI11 and runs the chosen
// subcommand. Exit codes: 0 success, 1 a failed action (the message names the
// input at fault), 2 a malformed command line.
#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>

#include "commands.h"
#include "common/message_text.h"

int main(int argc, char** argv) {
  CLI::App app{"bsg: Bullet-Safety-Gym in C++ - safe-RL environments and learners", "bsg"};
  app.set_version_flag("--version", std::string("bsg ") + BSG_VERSION);
  // No require_subcommand(): CLI11 would then report "a subcommand is
  // required" before naming an unknown word; we check for a missing
  // subcommand ourselves after parsing.
  app.require_subcommand(0, 1);

  bsg::cli::Action run;
  bsg::cli::add_train_command(app, run);
  bsg::cli::add_eval_command(app, run);
  bsg::cli::add_sweep_command(app, run);
  bsg::cli::add_table_command(app, run);
  bsg::cli::add_envs_command(app, run);
  bsg::cli::add_rollout_command(app, run);
  bsg::cli::add_bench_command(app, run);
  bsg::cli::add_collect_command(app, run);
  bsg::cli::add_dataset_command(app, run);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "bsg: " << e.what() << "\n"
              << "Run 'bsg --help' for the list of subcommands and options.\n";
    return 2;
  }
  if (!run) {
    std::cerr << "bsg: a subcommand is required\n" << app.help();
    return 2;
  }
  try {
    return run();
  } catch (const std::exception& e) {
    std::cerr << "bsg: error: " << bsg::printable_message(e.what()) << "\n";
    return 1;
  }
}
