// Runs the tuneray binary in a child process and captures what it did, so tests can check
// exit codes (and that no signal killed it) and messages.
#pragma once

#include <string>
#include <vector>

namespace tuneray::testing {

struct CommandResult {
  int exit_code = -1;     // valid when !signaled
  bool signaled = false;  // killed by a signal (a crash)
  int signal = 0;
  std::string output;  // stdout and stderr together
};

// Arguments are passed without a shell.
CommandResult run_tuneray(const std::vector<std::string>& args);
std::string tuneray_binary();

}  // namespace tuneray::testing
