// tuneray eval: the study of DESIGN §6 (search speedup, predictors vs search, overhead,
// roofline, break-even) with report, CSV and plots.
#include <fmt/core.h>

#include <iostream>
#include <memory>

#include "app/cli_parse.h"
#include "app/commands.h"
#include "bench/scene_paths.h"
#include "tuning/eval_report.h"
#include "tuning/eval_study.h"

namespace tuneray {

namespace {

struct EvalArgs {
  std::string profile = "quick";
  std::string out = "report";
  std::string db;
  std::vector<std::string> scenes;
  std::string scenes_dir;
  int cameras = 0, iterations = 0, repetitions = 0;
  std::string size;
  uint32_t spp = 0;
  std::string objective = "both";
  std::string scheduler = QualityOptions{}.wavefront ? "wavefront" : "tile";
  bool tuned_only = false;
  bool synthetic_costs = false;
  bool quiet = false;
  std::string command_line;
};

int run_eval(const EvalArgs& a) {
  std::string scenes_dir = find_shared_scenes_dir(a.scenes_dir);
  EvalProfile p = eval_profile(
      a.profile, scenes_dir.empty() ? std::vector<std::string>{} : shared_scene_json_files());
  p.scenes_dir = scenes_dir;
  if (!a.scenes.empty()) p.scenes = a.scenes;
  if (p.scenes.empty())
    throw std::invalid_argument("profile '" + a.profile +
                                "' needs the shared scenes (../shared/scenes) and this checkout's "
                                "scenes/*.json: not found (use --scenes-dir or $TUNERAY_SCENES, "
                                "or --scenes)");
  if (a.cameras > 0) p.cameras = a.cameras;
  if (a.iterations > 0) p.iterations = a.iterations;
  if (a.repetitions > 0) p.repetitions = a.repetitions;
  if (a.spp > 0) p.spp = a.spp;
  if (!a.size.empty()) std::tie(p.width, p.height) = parse_size(a.size);
  if (a.objective == "render")
    p.objectives = {Objective::kRender};
  else if (a.objective == "total")
    p.objectives = {Objective::kTotal};
  if (p.cameras < 2) throw std::invalid_argument("the study needs at least 2 cameras");
  p.wavefront = a.scheduler == "wavefront";
  p.native_in_space = !a.tuned_only;
  p.synthetic_costs = a.synthetic_costs;

  fmt::print(
      "eval profile {}: {} scene(s), {} cameras x {} frames, {}x{} {} spp, {} repetitions, {} "
      "scheduler, {}{} -> {}\n",
      p.name, p.scenes.size(), p.cameras, p.iterations, p.width, p.height, p.spp, p.repetitions,
      a.scheduler, p.native_in_space ? "backend tuned|native + BVH" : "tuned BVH only",
      p.synthetic_costs ? ", SYNTHETIC costs" : "", a.out);
  EvalPaths paths{a.out, a.db};
  EvalResults results = run_eval_study(p, paths, [&](const std::string& line) {
    if (!a.quiet) std::cout << line << std::endl;
  });
  std::string report = write_eval_report(results, a.out, a.command_line);
  fmt::print("wrote {}\n", report);
  return 0;
}

}  // namespace

CommandAction add_eval_command(CLI::App& app) {
  auto a = std::make_shared<EvalArgs>();
  CLI::App* cmd = app.add_subcommand("eval", "Run the autotuning study and write a report");
  cmd->add_option("--profile", a->profile, "quick, standard or paper")
      ->check(CLI::IsMember({"quick", "standard", "paper"}))
      ->capture_default_str();
  cmd->add_option("--out", a->out, "Output folder (report.md, CSV, plots/)")->capture_default_str();
  cmd->add_option("--db", a->db, "Tuning database (default OUT/eval.db); reruns resume from it");
  cmd->add_option("--scenes", a->scenes, "Scenes (overrides the profile)")->delimiter(',');
  cmd->add_option("--scenes-dir", a->scenes_dir, "Folder of the shared scenes");
  cmd->add_option("--cameras", a->cameras, "Cameras per scene")->check(CLI::Range(2, 100000));
  cmd->add_option("--iterations", a->iterations, "Search frames per camera")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--repetitions", a->repetitions, "Random train/validation splits")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--size", a->size, "Frame size WxH");
  cmd->add_option("--spp", a->spp, "Samples per pixel per frame")->check(CLI::Range(1, 4096));
  cmd->add_option("--objective", a->objective, "render, total or both")
      ->check(CLI::IsMember({"render", "total", "both"}))
      ->capture_default_str();
  cmd->add_option("--scheduler", a->scheduler, "Scheduler frames are measured on")
      ->check(CLI::IsMember({"tile", "wavefront"}))
      ->capture_default_str();
  cmd->add_flag("--tuned-only", a->tuned_only,
                "Search the tuned BVH's parameters only, without native Embree as a choice");
  cmd->add_flag("--synthetic-costs", a->synthetic_costs,
                "Testing only: replace every measurement by a deterministic made-up cost of "
                "(scene, camera, configuration); nothing is rendered and the figures mean nothing, "
                "but reruns and resumed runs write byte-identical reports");
  cmd->add_flag("--quiet,-q", a->quiet, "No per-camera lines");
  return [a, cmd] {
    a->command_line = "tuneray eval --profile " + a->profile + " --out " + a->out;
    for (const auto* opt : cmd->get_options())
      if (opt->count() > 0 && opt->get_name() != "--profile" && opt->get_name() != "--out" &&
          opt->get_name() != "--help")
        a->command_line += " " + opt->get_name() +
                           (opt->get_expected_min() == 0 ? "" : " " + opt->as<std::string>());
    return run_eval(*a);
  };
}

}  // namespace tuneray
