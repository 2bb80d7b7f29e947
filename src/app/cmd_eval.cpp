// tuneray eval: the study of DESIGN §6 (search speedup, predictors vs search, overhead,
// roofline, break-even) with report, CSV and plots.
#include <fmt/core.h>

#include <tbb/global_control.h>

#include <iostream>
#include <memory>

#include "app/cli_parse.h"
#include "app/commands.h"
#include "bench/scene_paths.h"
#include "tuner/hardware_signature.h"
#include "tuning/eval_ranks.h"
#include "tuning/eval_report.h"
#include "tuning/eval_study.h"
#include "tuning/mpi_ranks.h"
#include "tuning/rank_cores.h"

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
  bool seeded = false;
  bool synthetic_costs = false;
  bool mix_signatures = false;
  bool quiet = false;
  std::string command_line;
};

void print_eval_header(const EvalProfile& p, const EvalArgs& a) {
  fmt::print(
      "eval profile {}: {} scene(s), {} cameras x {} frames, {}x{} {} spp, {} repetitions, {} "
      "scheduler, {}{}{} -> {}\n",
      p.name, p.scenes.size(), p.cameras, p.iterations, p.width, p.height, p.spp, p.repetitions,
      a.scheduler, p.native_in_space ? "backend tuned|native + BVH" : "tuned BVH only",
      p.seeded ? ", seeded searches" : "", p.synthetic_costs ? ", SYNTHETIC costs" : "", a.out);
}

void write_report(const EvalResults& results, const EvalArgs& a) {
  std::string report = write_eval_report(results, a.out, a.command_line);
  fmt::print("wrote {}\n", report);
}

// Gives this rank its slice of the node's cores (rank_cores.h) and limits TBB to it; the
// lowest rank of each node says how the node is split. A failure to pin is reported and the
// rank runs unpinned.
std::unique_ptr<tbb::global_control> pin_rank(MpiSession& mpi) {
  const MpiSession::Node node = mpi.node();
  const auto split = split_node_cores(node.ranks, node.cores);
  if (!node.ranks.empty() && mpi.rank() == *std::min_element(node.ranks.begin(), node.ranks.end()))
    fmt::print("{}\n", describe_node_cores(node.ranks, node.cores, split));
  auto mine = split.find(mpi.rank());
  if (mine == split.end()) return nullptr;
  try {
    pin_process(mine->second);
  } catch (const std::exception& e) {
    fmt::print(stderr, "tuneray eval: rank {}: {}; running unpinned\n", mpi.rank(), e.what());
    return nullptr;
  }
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                               mine->second.size());
}

// `mpirun -n N tuneray eval ...`: rank 0 coordinates and alone writes the database and the
// report, the others measure (tuning/eval_ranks.h). Any failure ends every rank: a worker left
// waiting for a coordinator that is gone would hang the job.
int run_eval_on_ranks(const EvalProfile& p, const EvalArgs& a) {
  MpiSession mpi;
  std::unique_ptr<tbb::global_control> threads = pin_rank(mpi);
  std::unique_ptr<RankTransport> transport = mpi.transport();
  if (mpi.rank() != 0) {
    run_eval_worker(p, *transport, tuner::hardware_signature());
    return 0;
  }
  try {
    print_eval_header(p, a);
    fmt::print("{} ranks: rank 0 coordinates, {} measure\n", mpi.size(), mpi.size() - 1);
    auto print = [&](const std::string& line) {
      if (!a.quiet) std::cout << line << std::endl;
    };
    EvalResults results =
        run_eval_coordinator(p, EvalPaths{a.out, a.db}, *transport, a.mix_signatures, print, print);
    write_report(results, a);
  } catch (const std::exception& e) {
    std::cerr << "tuneray: error: " << e.what() << std::endl;
    mpi.abort(1);
  }
  return 0;
}

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
  p.seeded = a.seeded;
  p.synthetic_costs = a.synthetic_costs;

  const int ranks = mpirun_world_size();
  if (ranks > 1) {
    if (!mpi_compiled_in())
      throw std::invalid_argument(fmt::format(
          "started by mpirun as {} processes, but this tuneray was built without MPI: each would "
          "run the whole study into the same files (install libopenmpi-dev and reconfigure)",
          ranks));
    return run_eval_on_ranks(p, a);
  }
  print_eval_header(p, a);
  EvalStudyOptions options;
  options.mix_signatures = a.mix_signatures;
  EvalResults results = run_eval_study(
      p, EvalPaths{a.out, a.db},
      [&](const std::string& line) {
        if (!a.quiet) std::cout << line << std::endl;
      },
      options);
  write_report(results, a);
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
  cmd->add_flag("--seeded", a->seeded,
                "Start each search from the seeds tune gives its searches (our tree with Embree's "
                "BVH8 settings and variants) as well as random points; without it the paper's "
                "protocol (searches from the default configuration)");
  cmd->add_flag("--synthetic-costs", a->synthetic_costs,
                "Testing only: replace every measurement by a deterministic made-up cost of "
                "(scene, camera, configuration); nothing is rendered and the figures mean nothing, "
                "but reruns and resumed runs write byte-identical reports");
  cmd->add_flag("--mix-signatures", a->mix_signatures,
                "Accept samples measured on machines of another hardware signature (CPU model and "
                "core count) in one study; without it the study refuses them");
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
