// The `tuneray` subcommands. Each registers its options on the CLI and returns an exit code.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>

namespace tuneray {

// A subcommand's action runs after parsing; it returns the process exit code.
using CommandAction = std::function<int()>;

CommandAction add_render_command(CLI::App& app);
CommandAction add_info_command(CLI::App& app);
CommandAction add_bench_command(CLI::App& app);
CommandAction add_tune_command(CLI::App& app);
CommandAction add_eval_command(CLI::App& app);
CommandAction add_compare_command(CLI::App& app);

}  // namespace tuneray
