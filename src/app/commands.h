// The `tuneray` subcommands. Each registers its options on the CLI and returns an exit code.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>

#include "bench/accel_bench.h"
#include "bench/peers_bench.h"
#include "bench/quality_bench.h"
#include "bench/render_bench.h"

namespace tuneray {

// A subcommand's action runs after parsing; it returns the process exit code.
using CommandAction = std::function<int()>;

CommandAction add_render_command(CLI::App& app);
CommandAction add_info_command(CLI::App& app);
CommandAction add_bench_command(CLI::App& app);
CommandAction add_tune_command(CLI::App& app);
CommandAction add_eval_command(CLI::App& app);
CommandAction add_compare_command(CLI::App& app);
CommandAction add_view_command(CLI::App& app);

// The `bench` subcommands' runs (cmd_bench_*.cpp): the bench library's benchmark, printed.
int run_bench_render(const RenderBenchOptions& options);
int run_bench_peers(const PeersBenchOptions& options, const std::string& json);
int run_bench_quality(const QualityBenchOptions& options);
int run_bench_traversal(const AccelBenchOptions& options);
int run_bench_build(const AccelBenchOptions& options);

}  // namespace tuneray
