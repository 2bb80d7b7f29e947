#include "tuning/eval_report.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <ostream>

#include "image/atomic_file.h"
#include "tuning/eval_figures.h"
#include "tuning/eval_metrics.h"
#include "tuning/stats.h"

namespace tuneray {

namespace {

namespace fs = std::filesystem;

// Written aside and renamed on commit(): a failed or killed run never leaves a truncated file.
ReplacingFile open_out(const fs::path& path) {
  return ReplacingFile(path.string());
}

std::string num(double v) {
  return report_number(v);
}

std::vector<double> finite(const std::vector<double>& v) {
  std::vector<double> out;
  for (double x : v)
    if (std::isfinite(x)) out.push_back(x);
  return out;
}

double mean_of(const std::vector<double>& v) {
  double sum = 0;
  for (double x : v) sum += x;
  return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
}

std::vector<double> ratios_of(const std::vector<RatioInterval>& v) {
  std::vector<double> out;
  for (const RatioInterval& x : v) out.push_back(x.ratio);
  return out;
}

// The per-comparison bounds summarised by `statistic` (median or mean, as the ratio is).
TypicalInterval typical_interval(const std::vector<RatioInterval>& v,
                                 double (*statistic)(const std::vector<double>&)) {
  std::vector<double> lows, highs;
  for (const RatioInterval& x : v) {
    lows.push_back(x.low);
    highs.push_back(x.high);
  }
  return {statistic(lows), statistic(highs)};
}

// median() takes its values by copy: this is its shape as a statistic for typical_interval.
double median_of(const std::vector<double>& v) {
  return median(v);
}

// "1.234 [1.220, 1.250]": a ratio with its typical 95 % interval.
std::string with_interval(double value, const TypicalInterval& i) {
  return fmt::format("{} [{}, {}]", num(value), num(i.low), num(i.high));
}

void write_csvs(const EvalResults& r, const fs::path& dir) {
  auto cams = open_out(dir / "cameras.csv");
  cams << "scene,objective,camera,default_ms,converged_ms,best_ms,search_speedup,converged,"
          "search_frames,search_total_ms,converged_config,best_config,native_ms,"
          "native_speedup,search_speedup_low,search_speedup_high,native_speedup_low,"
          "native_speedup_high,candidates,rounds,ci_within_target,search_default_ms,"
          "search_window_load,search_default_frames,search_calibrated\n";
  for (const CameraRecord& c : r.cameras) {
    double total = 0;
    for (double ms : c.search_ms) total += ms;
    cams << fmt::format(
        "{},{},{},{},{},{},{},{},{},{},\"{}\",\"{}\",{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
        c.scene, c.objective, c.camera, num(c.default_ms), num(c.converged_ms), num(c.best_ms),
        num(c.search_speedup.ratio), c.converged ? 1 : 0, c.search_ms.size(), num(total),
        c.converged_config, c.best_config, num(c.native_ms), num(c.native_speedup.ratio),
        num(c.search_speedup.low), num(c.search_speedup.high), num(c.native_speedup.low),
        num(c.native_speedup.high), c.candidates, c.rounds, c.within_target ? 1 : 0,
        num(c.search_default_ms), num(c.search_window_load), c.search_default_frames,
        c.search_calibrated ? 1 : 0);
  }
  cams.commit();
  auto frames = open_out(dir / "search_frames.csv");
  frames << "scene,objective,camera,frame,cost_ms\n";
  for (const CameraRecord& c : r.cameras)
    for (size_t k = 0; k < c.search_ms.size(); ++k)
      frames << fmt::format("{},{},{},{},{}\n", c.scene, c.objective, c.camera, k,
                            num(c.search_ms[k]));
  frames.commit();
  auto preds = open_out(dir / "predictions.csv");
  preds << "scene,objective,repetition,camera,predictor,predicted_ms,search_total_ms,speedup,"
           "overhead_reduction,roofline,break_even,config,native_speedup,roofline_low,"
           "roofline_high,native_speedup_low,native_speedup_high\n";
  for (const PredictionRecord& p : r.predictions)
    preds << fmt::format("{},{},{},{},{},{},{},{},{},{},{},\"{}\",{},{},{},{},{}\n", p.scene,
                         p.objective, p.repetition, p.camera, p.predictor, num(p.predicted_ms),
                         num(p.search_total_ms), num(p.speedup), num(p.overhead_reduction),
                         num(p.roofline.ratio), num(p.break_even), p.config,
                         num(p.native_speedup.ratio), num(p.roofline.low), num(p.roofline.high),
                         num(p.native_speedup.low), num(p.native_speedup.high));
  preds.commit();
}

void write_summary_csv(const std::vector<EvalSummary>& summaries, const fs::path& dir) {
  auto f = open_out(dir / "summary.csv");
  f << "scene,objective,cameras,search_speedup_median,search_native_speedup_median,"
       "nn_speedup_geomean,rbf_speedup_geomean,nn_overhead_reduction_median,"
       "rbf_overhead_reduction_median,nn_roofline_mean,rbf_roofline_mean,nn_break_even_median,"
       "rbf_break_even_median,nn_never,rbf_never,nn_native_speedup_median,"
       "rbf_native_speedup_median,within_target,rounds_median,search_speedup_low,"
       "search_speedup_high,search_native_speedup_low,search_native_speedup_high,"
       "nn_roofline_low,nn_roofline_high,rbf_roofline_low,rbf_roofline_high,"
       "nn_native_speedup_low,nn_native_speedup_high,rbf_native_speedup_low,"
       "rbf_native_speedup_high\n";
  auto bounds = [](const TypicalInterval& i) { return num(i.low) + "," + num(i.high); };
  for (const EvalSummary& s : summaries)
    f << fmt::format(
        "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", s.scene,
        s.objective, s.cameras, num(s.search_speedup_median), num(s.search_native_speedup_median),
        num(s.nn_speedup_geomean), num(s.rbf_speedup_geomean), num(s.nn_overhead_reduction_median),
        num(s.rbf_overhead_reduction_median), num(s.nn_roofline_mean), num(s.rbf_roofline_mean),
        num(s.nn_break_even_median), num(s.rbf_break_even_median), s.nn_never, s.rbf_never,
        num(s.nn_native_speedup_median), num(s.rbf_native_speedup_median), s.within_target,
        num(s.rounds_median), bounds(s.search_speedup_interval),
        bounds(s.search_native_speedup_interval), bounds(s.nn_roofline_interval),
        bounds(s.rbf_roofline_interval), bounds(s.nn_native_speedup_interval),
        bounds(s.rbf_native_speedup_interval));
  f.commit();
}

// One objective's table per scene and its comparison with the published figures.
void write_objective_section(std::ostream& md, const std::vector<EvalSummary>& summaries,
                             const std::string& obj, const EvalProfile& p) {
  const bool render = obj == "render";
  md << "## Objective `" << obj << "` ("
     << (render ? "render time, progressive rendering" : "build + render time, real-time rendering")
     << ")\n\n"
     << fmt::format(
            "| scene | cameras | comparisons within ±{:g} % | search speedup "
            "(median) | search over native (median) | NN speedup over search (geo-mean) | RBF "
            "speedup (geo-mean) | NN overhead reduction (median) | RBF overhead reduction | NN "
            "roofline (mean) | RBF roofline | NN break-even (median frame, never) | RBF "
            "break-even | NN over native (median) | RBF over native "
            "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
            100 * p.compare_target);
  std::vector<double> nn_speed, rbf_speed, search_speed, nn_overhead, nn_roof, rbf_roof;
  std::vector<double> search_native;
  int comparisons = 0, within_target = 0, calibrated = 0;
  std::vector<double> loads;
  for (const EvalSummary& s : summaries) {
    if (s.objective != obj) continue;
    calibrated += s.search_calibrated;
    if (s.search_window_load_median > 0) loads.push_back(s.search_window_load_median);
    md << fmt::format(
        "| {} | {} | {} of {}, median {} rounds | {} | {} | {} | {} | {} | {} | {} | {} "
        "| {} ({}) | {} ({}) | {} | {} |\n",
        s.scene, s.cameras, s.within_target, s.cameras, num(s.rounds_median),
        with_interval(s.search_speedup_median, s.search_speedup_interval),
        with_interval(s.search_native_speedup_median, s.search_native_speedup_interval),
        num(s.nn_speedup_geomean), num(s.rbf_speedup_geomean), num(s.nn_overhead_reduction_median),
        num(s.rbf_overhead_reduction_median),
        with_interval(s.nn_roofline_mean, s.nn_roofline_interval),
        with_interval(s.rbf_roofline_mean, s.rbf_roofline_interval), num(s.nn_break_even_median),
        s.nn_never, num(s.rbf_break_even_median), s.rbf_never,
        with_interval(s.nn_native_speedup_median, s.nn_native_speedup_interval),
        with_interval(s.rbf_native_speedup_median, s.rbf_native_speedup_interval));
    comparisons += s.cameras;
    within_target += s.within_target;
    search_native.push_back(s.search_native_speedup_median);
    if (s.nn_speedup_geomean > 0) nn_speed.push_back(s.nn_speedup_geomean);
    if (s.rbf_speedup_geomean > 0) rbf_speed.push_back(s.rbf_speedup_geomean);
    search_speed.push_back(s.search_speedup_median);
    nn_overhead.push_back(s.nn_overhead_reduction_median);
    nn_roof.push_back(s.nn_roofline_mean);
    rbf_roof.push_back(s.rbf_roofline_mean);
  }
  auto max_of = [](const std::vector<double>& v) {
    return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
  };
  auto min_of = [](const std::vector<double>& v) {
    return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end());
  };
  md << "\n| figure | ours | published (Herveau et al.) |\n|---|---|---|\n"
     << fmt::format(
            "| search speedup over default, median per scene (best scene) | {} | 1.11 "
            "(sponza); 1.02–1.04 elsewhere |\n",
            num(max_of(search_speed)))
     << fmt::format(
            "| search speedup over native Embree, median per scene (worst scene – best "
            "scene) | {} – {} | — (target: >= 1.10 median, never below 1.0) |\n",
            num(min_of(search_native)), num(max_of(search_native)))
     << fmt::format("| NN speedup over search, geo-mean over scenes | {} | {} |\n",
                    num(geometric_mean(nn_speed)), render ? "1.05" : "1.12")
     << fmt::format("| RBF speedup over search, geo-mean over scenes | {} | {} |\n",
                    num(geometric_mean(rbf_speed)), render ? "1.04" : "—")
     << fmt::format("| best overhead reduction (NN, median per scene) | {} % | up to {} |\n",
                    num(100 * max_of(nn_overhead)), render ? "87.5 %" : "89.3 %")
     << fmt::format("| roofline, mean over scenes | NN {} %, RBF {} % | {} |\n",
                    num(100 * mean_of(nn_roof)), num(100 * mean_of(rbf_roof)),
                    render ? "> 95 %" : "NN 92 %, RBF 83 %")
     << fmt::format(
            "| comparisons whose every 95 % interval reached ±{:g} % before the cap of {} "
            "rounds | {} of {} | — (none published) |\n",
            100 * p.compare_target, p.compare_max_rounds, within_target, comparisons)
     << fmt::format(
            "| searches' machine load against their comparisons' (the default configuration's "
            "frames in both windows), median per scene (lowest – highest scene); cameras whose "
            "search frames were divided by it | {} – {}; {} of {} | — |\n\n",
            num(min_of(loads)), num(max_of(loads)), calibrated, comparisons);
}

}  // namespace

std::string report_number(double v) {
  if (std::isinf(v)) return "inf";
  return fmt::format("{:.3f}", v);
}

std::vector<EvalSummary> summarise(const EvalResults& r) {
  std::vector<EvalSummary> out;
  std::vector<std::pair<std::string, std::string>> keys;
  for (const CameraRecord& c : r.cameras)
    if (std::find(keys.begin(), keys.end(), std::pair{c.scene, c.objective}) == keys.end())
      keys.emplace_back(c.scene, c.objective);
  for (const auto& [scene, obj] : keys) {
    EvalSummary s;
    s.scene = scene;
    s.objective = obj;
    std::vector<RatioInterval> search, search_native;
    std::vector<double> rounds, loads;
    for (const CameraRecord& c : r.cameras)
      if (c.scene == scene && c.objective == obj) {
        search.push_back(c.search_speedup);
        search_native.push_back(c.native_speedup);
        rounds.push_back(c.rounds);
        s.within_target += c.within_target ? 1 : 0;
        if (c.search_window_load > 0) loads.push_back(c.search_window_load);
        s.search_calibrated += c.search_calibrated ? 1 : 0;
      }
    s.search_window_load_median = median(loads);
    s.cameras = static_cast<int>(search.size());
    s.rounds_median = median(rounds);
    s.search_speedup_median = median(ratios_of(search));
    s.search_speedup_interval = typical_interval(search, median_of);
    s.search_native_speedup_median = median(ratios_of(search_native));
    s.search_native_speedup_interval = typical_interval(search_native, median_of);
    std::map<std::string, std::vector<double>> speed, overhead, breakeven;
    std::map<std::string, std::vector<RatioInterval>> roof, native;
    std::map<std::string, int> never;
    for (const PredictionRecord& p : r.predictions) {
      if (p.scene != scene || p.objective != obj) continue;
      speed[p.predictor].push_back(p.speedup);
      native[p.predictor].push_back(p.native_speedup);
      overhead[p.predictor].push_back(p.overhead_reduction);
      roof[p.predictor].push_back(p.roofline);
      if (std::isfinite(p.break_even))
        breakeven[p.predictor].push_back(p.break_even);
      else
        ++never[p.predictor];
    }
    s.nn_speedup_geomean = geometric_mean(speed["nn"]);
    s.rbf_speedup_geomean = geometric_mean(speed["rbf"]);
    s.nn_overhead_reduction_median = median(finite(overhead["nn"]));
    s.rbf_overhead_reduction_median = median(finite(overhead["rbf"]));
    s.nn_roofline_mean = mean_of(ratios_of(roof["nn"]));
    s.nn_roofline_interval = typical_interval(roof["nn"], mean_of);
    s.rbf_roofline_mean = mean_of(ratios_of(roof["rbf"]));
    s.rbf_roofline_interval = typical_interval(roof["rbf"], mean_of);
    s.nn_break_even_median = median(breakeven["nn"]);
    s.rbf_break_even_median = median(breakeven["rbf"]);
    s.nn_never = never["nn"];
    s.rbf_never = never["rbf"];
    s.nn_native_speedup_median = median(ratios_of(native["nn"]));
    s.nn_native_speedup_interval = typical_interval(native["nn"], median_of);
    s.rbf_native_speedup_median = median(ratios_of(native["rbf"]));
    s.rbf_native_speedup_interval = typical_interval(native["rbf"], median_of);
    out.push_back(s);
  }
  return out;
}

std::string write_eval_report(const EvalResults& r, const std::string& out_dir,
                              const std::string& command_line) {
  fs::path dir(out_dir);
  fs::create_directories(dir / "plots");
  remove_stale_temporaries(dir.string());
  remove_stale_temporaries((dir / "plots").string());
  write_csvs(r, dir);
  std::vector<EvalSummary> summaries = summarise(r);
  write_summary_csv(summaries, dir);
  write_eval_figures(r, summaries, (dir / "plots").string());
  bool plotted = draw_eval_figures((dir / "plots").string());

  const EvalProfile& p = r.profile;
  fs::path report_path = dir / "report.md";
  auto md = open_out(report_path);
  md << "# BVH autotuning study (profile `" << p.name << "`)\n\n"
     << "Command: `" << command_line << "`\n\n"
     << (p.synthetic_costs
             ? "**Synthetic costs** (`--synthetic-costs`): every frame cost below is a made-up "
               "deterministic function of scene, camera and configuration, not a measurement. "
               "This report tests the study's machinery (resume, reproducibility) and says "
               "nothing about the renderer.\n\n"
             : "")
     << fmt::format(
            "Protocol: {} cameras per scene along its camera path, {} search frames per "
            "camera (each builds the BVH as the objective requires and renders {} spp at "
            "{}x{}, {} bounces, {} scheduler); the search space is {}{}; predictors trained "
            "on {:.0f} % of the cameras and validated on the rest, {} random splits. At each "
            "camera, every configuration compared (the default, native Embree, the search's "
            "converged configuration and best sample, every prediction) is re-measured in one "
            "comparison: an untimed frame of each, then rounds of one frame each in rotating "
            "order, from {} rounds until the 95 % confidence interval of the ratio between any "
            "two of them is within ±{:g} %, at most {} rounds. Ratios are the medians of the "
            "per-round ratios, shown with their distribution-free 95 % interval (order "
            "statistics of binomial ranks) in brackets (over cameras: the median, or for the "
            "roofline the mean, of the single comparisons' bounds); costs are the default "
            "configuration's median cost times the median per-round ratio to it.\n\n",
            p.cameras, p.iterations, p.spp, p.width, p.height, p.max_bounces,
            p.wavefront ? "wavefront" : "tile",
            p.native_in_space ? "the backend (tuned BVH or native Embree) and the BVH parameters"
                              : "the tuned BVH's parameters only",
            p.seeded ? ", each search seeded as `tune` seeds its searches (`--seeded`: our tree "
                       "with Embree's BVH8 settings and its variants in the first simplex)"
                     : "",
            100 * p.train_fraction, p.repetitions, p.compare_min_rounds, 100 * p.compare_target,
            p.compare_max_rounds);
  for (const std::string obj : {"render", "total"}) {
    bool any = false;
    for (const EvalSummary& s : summaries) any |= s.objective == obj;
    if (!any) continue;
    write_objective_section(md.stream(), summaries, obj, p);
    if (plotted) {
      for (const char* figure : {"search_speedup", "predictor_speedup", "roofline", "break_even"})
        md << "![" << figure << "](plots/" << figure << "_" << obj << ".png)\n";
      for (const EvalSummary& s : summaries)
        if (s.objective == obj)
          md << "![tuning trace " << s.scene << "](plots/" << trace_figure_stem(s.scene, obj)
             << ".png)\n";
      md << "\n";
    }
  }
  if (!plotted) md << "Plots: gnuplot was not available or failed; the scripts are in plots/.\n\n";
  md << "Definitions: *search speedup* = default / converged configuration; *over native* = "
        "native Embree (medium quality, as `render --accel native`) / the converged or "
        "predicted configuration; *speedup over search* = accumulated time of the search's "
        "frames / (frames x the prediction's cost); *overhead reduction* = 1 - (prediction's "
        "accumulated time - frames x best) / (search's accumulated time - frames x best); "
        "*roofline* = best / predicted cost, where *best* is the fastest configuration of the "
        "camera's comparison; *break-even* = first frame at which the search's accumulated time "
        "is no longer above the prediction's (never = the search's converged configuration is "
        "not faster than the prediction). Every cost and ratio except the search's own frames "
        "comes from the camera's comparison. A refused build counts as a frame at the cost the "
        "search measured for the default configuration. Raw data: cameras.csv, "
        "search_frames.csv, predictions.csv, summary.csv.\n";
  md.commit();
  return report_path.string();
}

}  // namespace tuneray
