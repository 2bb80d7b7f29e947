// Runs a program in a child process with some environment variables set or removed, and
// captures its exit and its output, so tests can check exit codes (and that no signal killed
// it) and messages (the viewer tests also remove DISPLAY, or run under xvfb-run).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace tuneray::testing {

struct ProgramResult {
  int exit_code = -1;     // valid when !signaled
  bool signaled = false;  // killed by a signal (a crash)
  int signal = 0;
  std::string output;  // stdout and stderr together
};

// Arguments are passed without a shell; argv[0] is looked up on PATH. `environment`: a value
// sets the variable, nullopt removes it.
ProgramResult run_program(
    const std::vector<std::string>& argv,
    const std::map<std::string, std::optional<std::string>>& environment = {});

// The tuneray binary under test ($TUNERAY_BIN, set by ctest).
std::string tuneray_binary();

}  // namespace tuneray::testing
