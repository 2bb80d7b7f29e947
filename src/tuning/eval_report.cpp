#include "tuning/eval_report.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>

#include "image/atomic_file.h"
#include "tuning/eval_metrics.h"
#include "tuning/stats.h"

namespace tuneray {

namespace {

namespace fs = std::filesystem;

// Written aside and renamed on commit(): a failed or killed run never leaves a truncated file.
ReplacingFile open_out(const fs::path& path) {
  return ReplacingFile(path.string());
}

// Numbers in CSV and report share one format, so the report can be checked against the CSV.
std::string num(double v) {
  if (std::isinf(v)) return "inf";
  return fmt::format("{:.3f}", v);
}

std::vector<double> finite(const std::vector<double>& v) {
  std::vector<double> out;
  for (double x : v)
    if (std::isfinite(x)) out.push_back(x);
  return out;
}

void write_csvs(const EvalResults& r, const fs::path& dir) {
  auto cams = open_out(dir / "cameras.csv");
  cams << "scene,objective,camera,default_ms,converged_ms,best_ms,search_speedup,converged,"
          "search_frames,search_total_ms,converged_config,best_config,native_ms,"
          "native_speedup\n";
  for (const CameraRecord& c : r.cameras) {
    double total = 0;
    for (double ms : c.search_ms) total += ms;
    cams << fmt::format("{},{},{},{},{},{},{},{},{},{},\"{}\",\"{}\",{},{}\n", c.scene, c.objective,
                        c.camera, num(c.default_ms), num(c.converged_ms), num(c.best_ms),
                        num(c.search_speedup()), c.converged ? 1 : 0, c.search_ms.size(),
                        num(total), c.converged_config, c.best_config, num(c.native_ms),
                        num(c.native_speedup()));
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
           "overhead_reduction,roofline,break_even,config,native_speedup\n";
  for (const PredictionRecord& p : r.predictions)
    preds << fmt::format("{},{},{},{},{},{},{},{},{},{},{},\"{}\",{}\n", p.scene, p.objective,
                         p.repetition, p.camera, p.predictor, num(p.predicted_ms),
                         num(p.search_total_ms), num(p.speedup), num(p.overhead_reduction),
                         num(p.roofline), num(p.break_even), p.config, num(p.native_speedup));
  preds.commit();
}

// gnuplot script for one figure, written as both PNG and SVG. The image goes to `outfile` when
// the caller defines it (run_gnuplot draws aside and renames), else straight to its name.
void write_plot(const fs::path& dir, const std::string& stem, const std::string& body) {
  for (const char* kind : {"png", "svg"}) {
    auto f = open_out(dir / (stem + "." + kind + ".gp"));
    if (std::string(kind) == "png")
      f << "set terminal pngcairo size 900,500 font ',10'\n";
    else
      f << "set terminal svg size 900,500 font 'sans,10'\n";
    f << "if (!exists('outfile')) outfile = '" << stem << "." << kind << "'\n"
      << "set output outfile\n"
      << body;
    f.commit();
  }
}

bool run_gnuplot(const fs::path& dir) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) return false;
  bool ok = true;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".gp") {
      const fs::path image = dir / entry.path().stem();
      try {
        replace_file(image.string(), [&](const std::string& temporary) {
          // gnuplot runs in `dir`; the temporary lies beside the image there.
          std::string cmd = fmt::format("cd '{}' && gnuplot -e \"outfile='{}'\" '{}' 2>/dev/null",
                                        dir.string(), fs::path(temporary).filename().string(),
                                        entry.path().filename().string());
          if (std::system(cmd.c_str()) != 0 || !fs::exists(temporary))
            throw std::runtime_error("gnuplot failed on " + entry.path().string());
        });
      } catch (const std::runtime_error&) {
        ok = false;
      }
    }
  return ok;
}

void write_plots(const EvalResults& r, const std::vector<EvalSummary>& summaries,
                 const fs::path& dir) {
  std::set<std::string> objectives;
  std::vector<std::string> scenes;
  for (const EvalSummary& s : summaries) {
    objectives.insert(s.objective);
    if (std::find(scenes.begin(), scenes.end(), s.scene) == scenes.end()) scenes.push_back(s.scene);
  }
  std::string xtics = "set xtics (";
  for (size_t i = 0; i < scenes.size(); ++i)
    xtics += fmt::format("{}'{}' {}", i ? ", " : "", scenes[i], i + 1);
  xtics += ") rotate by -20\nset xrange [0.5:" + std::to_string(scenes.size() + 0.5) + "]\n";
  auto scene_index = [&](const std::string& s) {
    return static_cast<int>(std::find(scenes.begin(), scenes.end(), s) - scenes.begin() + 1);
  };

  // One box per (scene, series): each series is a block of its own in the data file (gnuplot's
  // box plot cannot filter rows), plotted with `index`.
  using Series = std::map<std::pair<int, int>, std::vector<double>>;
  auto box_plot = [&](const std::string& file, const Series& series) {
    auto d = open_out(dir / file);
    std::string plot;
    int block = 0;
    double lo = 1.0, hi = 1.0;  // the reference line y = 1 stays in view
    for (const auto& [key, values] : series) {
      if (values.empty()) continue;
      for (double v : values)
        if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
      if (block > 0) d << "\n\n";
      for (double v : values) d << num(v) << '\n';
      auto [scene, k] = key;
      double x = series.rbegin()->first.second > 1 ? scene + (k == 1 ? -0.18 : 0.18) : scene;
      plot += fmt::format("{}'{}' index {} using ({}):1 with boxplot lc {}",
                          block == 0 ? "plot " : ", ", file, block, x, k);
      ++block;
    }
    d.commit();
    // gnuplot 5.4 cannot autoscale y for box plots at fixed x: give the range.
    double pad = 0.05 * (hi - lo) + 1e-3;
    std::string range = fmt::format("set yrange [{}:{}]\n", lo - pad, hi + pad);
    return range + (plot.empty() ? std::string("plot 1 with lines lc 'gray'\n")
                                 : plot + ", 1 with lines lc 'gray'\n");
  };
  const std::string box_style =
      "set style boxplot outliers pointtype 7\nset boxwidth 0.3\n"
      "set style fill solid 0.3\nset grid y\nunset key\n";

  for (const std::string& obj : objectives) {
    Series search, predicted;
    for (const CameraRecord& c : r.cameras)
      if (c.objective == obj) {
        search[{scene_index(c.scene), 1}].push_back(c.search_speedup());
        search[{scene_index(c.scene), 2}].push_back(c.native_speedup());
      }
    for (const PredictionRecord& pr : r.predictions)
      if (pr.objective == obj)
        predicted[{scene_index(pr.scene), pr.predictor == "nn" ? 1 : 2}].push_back(pr.speedup);
    write_plot(dir, "search_speedup_" + obj,
               "set title 'Converged search per camera (" + obj +
                   "): left over the default configuration, right over native Embree'\n"
                   "set ylabel 'speedup'\n" +
                   box_style + xtics + box_plot("search_speedup_" + obj + ".dat", search));
    write_plot(dir, "predictor_speedup_" + obj,
               "set title 'Prediction vs search, accumulated frame time (" + obj +
                   "): left NN, right RBF'\nset ylabel 'speedup over search'\n" + box_style +
                   xtics + box_plot("predictor_speedup_" + obj + ".dat", predicted));

    auto roof = open_out(dir / ("roofline_" + obj + ".dat"));
    auto be = open_out(dir / ("break_even_" + obj + ".dat"));
    int finite_break_evens = 0;
    for (const PredictionRecord& pr : r.predictions) {
      if (pr.objective != obj) continue;
      int k = pr.predictor == "nn" ? 1 : 2;
      roof << pr.camera + (k == 1 ? 0.0 : 0.3) + 100 * (scene_index(pr.scene) - 1) << ' '
           << num(pr.roofline) << ' ' << k << '\n';
      if (std::isfinite(pr.break_even)) {
        be << pr.break_even << ' ' << k << '\n';
        ++finite_break_evens;
      }
    }
    roof.commit();
    be.commit();
    write_plot(
        dir, "roofline_" + obj,
        "set title 'Fraction of the best known configuration (" + obj +
            ")'\n"
            "set xlabel 'camera (100 x scene index + camera)'\nset ylabel 'best / predicted'\n"
            "set yrange [0:1.1]\nset grid\nset key bottom right\n"
            "plot 'roofline_" +
            obj +
            ".dat' using 1:($3==1?$2:1/0) title 'NN' pt 7 ps 0.6, "
            "'' using 1:($3==2?$2:1/0) title 'RBF' pt 5 ps 0.6\n");
    // Break-even frames span orders of magnitude: quarter-decade bins on a log axis. With no
    // finite break-even at all there is nothing to bin (gnuplot would refuse the empty log
    // axis): the plot says so instead.
    const std::string be_title =
        "set title 'Break-even frame: when search pays for its exploration (" + obj +
        "; never-cases not shown)'\nset xlabel 'frame'\n"
        "set ylabel 'count'\nset grid y\n";
    write_plot(dir, "break_even_" + obj,
               finite_break_evens == 0
                   ? be_title +
                         "set label 'the search never paid off: every prediction was at least as "
                         "fast as its result' at graph 0.5,0.5 center\n"
                         "set xrange [1:100]\nset yrange [0:1]\nplot NaN notitle\n"
                   : be_title +
                         "set logscale x\nbin(x) = 10**(0.25*floor(4*log10(x)))\n"
                         "plot 'break_even_" +
                         obj +
                         ".dat' using (bin($1)):($2==1?1:0) smooth frequency with impulses lw 8 "
                         "title 'NN', '' using (bin($1)*1.12):($2==2?1:0) smooth frequency with "
                         "impulses lw 8 title 'RBF'\n");
  }
}

}  // namespace

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
    std::vector<double> search, search_native;
    for (const CameraRecord& c : r.cameras)
      if (c.scene == scene && c.objective == obj) {
        search.push_back(c.search_speedup());
        search_native.push_back(c.native_speedup());
      }
    s.cameras = static_cast<int>(search.size());
    s.search_speedup_median = median(search);
    s.search_native_speedup_median = median(search_native);
    std::map<std::string, std::vector<double>> speed, overhead, roof, breakeven, native;
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
    auto mean = [](const std::vector<double>& v) {
      double sum = 0;
      for (double x : v) sum += x;
      return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
    };
    s.nn_speedup_geomean = geometric_mean(speed["nn"]);
    s.rbf_speedup_geomean = geometric_mean(speed["rbf"]);
    s.nn_overhead_reduction_median = median(finite(overhead["nn"]));
    s.rbf_overhead_reduction_median = median(finite(overhead["rbf"]));
    s.nn_roofline_mean = mean(roof["nn"]);
    s.rbf_roofline_mean = mean(roof["rbf"]);
    s.nn_break_even_median = median(breakeven["nn"]);
    s.rbf_break_even_median = median(breakeven["rbf"]);
    s.nn_never = never["nn"];
    s.rbf_never = never["rbf"];
    s.nn_native_speedup_median = median(native["nn"]);
    s.rbf_native_speedup_median = median(native["rbf"]);
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
  {
    auto f = open_out(dir / "summary.csv");
    f << "scene,objective,cameras,search_speedup_median,search_native_speedup_median,"
         "nn_speedup_geomean,rbf_speedup_geomean,nn_overhead_reduction_median,"
         "rbf_overhead_reduction_median,nn_roofline_mean,rbf_roofline_mean,nn_break_even_median,"
         "rbf_break_even_median,nn_never,rbf_never,nn_native_speedup_median,"
         "rbf_native_speedup_median\n";
    for (const EvalSummary& s : summaries)
      f << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", s.scene, s.objective,
                       s.cameras, num(s.search_speedup_median), num(s.search_native_speedup_median),
                       num(s.nn_speedup_geomean), num(s.rbf_speedup_geomean),
                       num(s.nn_overhead_reduction_median), num(s.rbf_overhead_reduction_median),
                       num(s.nn_roofline_mean), num(s.rbf_roofline_mean),
                       num(s.nn_break_even_median), num(s.rbf_break_even_median), s.nn_never,
                       s.rbf_never, num(s.nn_native_speedup_median),
                       num(s.rbf_native_speedup_median));
    f.commit();
  }
  write_plots(r, summaries, dir / "plots");
  bool plotted = run_gnuplot(dir / "plots");

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
            "{}x{}, {} bounces, {} scheduler); the search space is {}; predictors trained "
            "on {:.0f} % of the cameras and validated on the rest, {} random splits. Every "
            "configuration compared, native Embree included, is re-measured live (median of "
            "{}).\n\n",
            p.cameras, p.iterations, p.spp, p.width, p.height, p.max_bounces,
            p.wavefront ? "wavefront" : "tile",
            p.native_in_space ? "the backend (tuned BVH or native Embree) and the BVH parameters"
                              : "the tuned BVH's parameters only",
            100 * p.train_fraction, p.repetitions, p.measure_repeats);
  for (const std::string obj : {"render", "total"}) {
    bool any = false;
    for (const EvalSummary& s : summaries) any |= s.objective == obj;
    if (!any) continue;
    md << "## Objective `" << obj << "` ("
       << (obj == std::string("render") ? "render time, progressive rendering"
                                        : "build + render time, real-time rendering")
       << ")\n\n"
       << "| scene | cameras | search speedup (median) | search over native (median) | NN "
          "speedup over search (geo-mean) | RBF speedup (geo-mean) | NN overhead reduction "
          "(median) | RBF overhead reduction | NN roofline (mean) | RBF roofline | NN break-even "
          "(median frame, never) | RBF break-even | NN over native (median) | RBF over native "
          "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    std::vector<double> nn_speed, rbf_speed, search_speed, nn_overhead, nn_roof, rbf_roof;
    std::vector<double> search_native;
    for (const EvalSummary& s : summaries) {
      if (s.objective != obj) continue;
      md << fmt::format(
          "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} ({}) | {} ({}) | {} | {} |\n",
          s.scene, s.cameras, num(s.search_speedup_median), num(s.search_native_speedup_median),
          num(s.nn_speedup_geomean), num(s.rbf_speedup_geomean),
          num(s.nn_overhead_reduction_median), num(s.rbf_overhead_reduction_median),
          num(s.nn_roofline_mean), num(s.rbf_roofline_mean), num(s.nn_break_even_median),
          s.nn_never, num(s.rbf_break_even_median), s.rbf_never, num(s.nn_native_speedup_median),
          num(s.rbf_native_speedup_median));
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
    auto mean_of = [](const std::vector<double>& v) {
      double sum = 0;
      for (double x : v) sum += x;
      return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
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
                      num(geometric_mean(nn_speed)), obj == std::string("render") ? "1.05" : "1.12")
       << fmt::format("| RBF speedup over search, geo-mean over scenes | {} | {} |\n",
                      num(geometric_mean(rbf_speed)), obj == std::string("render") ? "1.04" : "—")
       << fmt::format("| best overhead reduction (NN, median per scene) | {} % | up to {} |\n",
                      num(100 * max_of(nn_overhead)),
                      obj == std::string("render") ? "87.5 %" : "89.3 %")
       << fmt::format("| roofline, mean over scenes | NN {} %, RBF {} % | {} |\n\n",
                      num(100 * mean_of(nn_roof)), num(100 * mean_of(rbf_roof)),
                      obj == std::string("render") ? "> 95 %" : "NN 92 %, RBF 83 %");
    if (plotted)
      md << "![search speedup](plots/search_speedup_" << obj << ".png)\n"
         << "![predictor speedup](plots/predictor_speedup_" << obj << ".png)\n"
         << "![roofline](plots/roofline_" << obj << ".png)\n"
         << "![break-even](plots/break_even_" << obj << ".png)\n\n";
  }
  if (!plotted) md << "Plots: gnuplot was not available or failed; the scripts are in plots/.\n\n";
  md << "Definitions: *search speedup* = default / converged configuration, both re-measured "
        "live; *over native* = native Embree (medium quality, as `render --accel native`) / the "
        "converged or predicted configuration, re-measured live the same way; *speedup over "
        "search* = accumulated time of the search's frames / (frames x the "
        "prediction's cost); *overhead reduction* = 1 - (prediction's accumulated time - frames "
        "x best) / (search's accumulated time - frames x best); *roofline* = best / predicted "
        "cost; *break-even* = first frame at which the search's accumulated time is no longer "
        "above the prediction's (never = the search's converged configuration is not faster "
        "than the prediction). A refused build counts as a frame at the default configuration's "
        "cost. Raw data: cameras.csv, search_frames.csv, predictions.csv, summary.csv.\n";
  md.commit();
  return report_path.string();
}

}  // namespace tuneray
