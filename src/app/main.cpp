// tuneray: a CPU path tracer that tunes its own BVH. See README.md and `tuneray --help`.
#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>
#include <vector>

#include "app/cli_parse.h"
#include "app/commands.h"

int main(int argc, char** argv) {
  CLI::App app{"tuneray: a CPU path tracer that tunes its own acceleration structure"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "tuneray 0.1");

  std::vector<std::pair<CLI::App*, tuneray::CommandAction>> commands;
  auto add = [&](tuneray::CommandAction (*add_command)(CLI::App&)) {
    size_t before = app.get_subcommands({}).size();
    tuneray::CommandAction action = add_command(app);
    commands.emplace_back(app.get_subcommands({})[before], std::move(action));
  };
  add(&tuneray::add_render_command);
  add(&tuneray::add_info_command);
  add(&tuneray::add_bench_command);
  add(&tuneray::add_tune_command);
  add(&tuneray::add_eval_command);
  add(&tuneray::add_compare_command);
  add(&tuneray::add_view_command);

  tuneray::refuse_non_finite_numbers(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    for (auto& [sub, action] : commands)
      if (sub->parsed()) return action();
  } catch (const std::exception& e) {
    std::cerr << "tuneray: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
