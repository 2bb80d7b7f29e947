// Runs the tuneray binary in a child process (common/run_program.h) and captures what it did.
#pragma once

#include <string>
#include <vector>

#include "common/run_program.h"

namespace tuneray::testing {

using CommandResult = ProgramResult;

// `args` follow the binary's path; no shell.
CommandResult run_tuneray(const std::vector<std::string>& args);

}  // namespace tuneray::testing
