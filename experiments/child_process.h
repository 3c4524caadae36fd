// Starting a child program with its output appended to a log file, and
// reaping children without blocking (POSIX fork/exec/waitpid). Children stay
// in the parent's process group, so that a signal to the group (Ctrl-C, or
// kill -- -PGID) reaches them too. A child starts with no signal blocked,
// whatever the parent blocks (a sweep blocks its stop signals).
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace bsg::experiments {

struct ChildCommand {
  std::vector<std::string> argv;  // argv[0] is looked up in PATH if it has no '/'
  std::vector<std::pair<std::string, std::string>> environment;  // added to ours
  std::filesystem::path working_dir;  // empty: ours
  std::filesystem::path log_file;     // stdout and stderr, appended; stdin is /dev/null
  int inherited_fd = -1;              // a descriptor the program keeps open (e.g. a lock)
};

// Throws std::runtime_error naming the program or log file if it cannot start.
// A program that cannot be executed exits with code 127 (its log says why).
pid_t start_child(const ChildCommand& command);

struct ChildExit {
  pid_t pid = 0;
  int exit_code = -1;  // -1 if killed by a signal
  int signal = 0;
};

// One child that has exited, if any (never blocks).
std::optional<ChildExit> reap_exited_child();

// "SIGTERM", "SIGINT", ... ("signal N" if it has no name).
std::string signal_name(int signal);

// "exit code 3", "killed by signal 9 (Killed)".
std::string describe(const ChildExit& exit);

// The path of the running program (/proc/self/exe).
std::filesystem::path current_executable();

// Shell-quoted words joined by spaces, for logs and messages.
std::string command_line_text(const std::vector<std::string>& argv);

}  // namespace bsg::experiments
