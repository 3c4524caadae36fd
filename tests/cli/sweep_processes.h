// Starting `bsg sweep` in its own process group from a CLI test, and counting
// the processes of that group that have not ended, so that a test can tell
// whether a sweep left children behind.
#pragma once

#include <signal.h>
#include <sys/types.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace bsg::testing {

// Processes of group `group` that have not ended yet (zombies have ended: their
// locks are released even if nobody has reaped them), from /proc/<pid>/stat.
inline int live_processes_in_group(pid_t group) {
  int live = 0;
  for (const std::filesystem::directory_entry& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(entry.path() / "stat");
    std::string line;
    if (!std::getline(stat, line)) continue;  // the process ended meanwhile
    // Fields after the ")" closing the command name: state ppid pgrp ...
    std::istringstream fields(line.substr(line.rfind(')') + 1));
    char state = 0;
    long parent = 0;
    long process_group = 0;
    fields >> state >> parent >> process_group;
    if (process_group == group && state != 'Z' && state != 'X') ++live;
  }
  return live;
}

// The sweep in its own process group, output to `log`; returns its pid.
inline pid_t start_sweep_in_own_group(const std::string& arguments, const std::filesystem::path& log) {
  const std::string command = std::string(BSG_BINARY) + " sweep " + arguments + " > '" + log.string() + "' 2>&1";
  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  setpgid(pid, pid);  // also here, so that the kill below cannot race the child's call
  return pid;
}

}  // namespace bsg::testing
