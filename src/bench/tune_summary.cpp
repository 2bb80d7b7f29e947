#include "bench/tune_summary.h"

#include "tuning/stats.h"

namespace tuneray {

TuneSummary summarize_tune(const TuneReport& report) {
  std::vector<double> speedups, vs_native;
  TuneSummary s;
  for (const auto& c : report.cameras) {
    speedups.push_back(c.speedup());
    vs_native.push_back(c.vs_native());
    s.searched += c.mode == "search";
    s.tuned += c.backend == "tuned";
    s.capped += !c.compare_within_target;
    s.race_changed += c.race_changed_choice;
    s.race_frames += c.race_frames;
    s.search_frames += c.frames;
    s.fallbacks += !c.fallback.empty();
  }
  s.speedup_median = median(speedups);
  s.speedup_geomean = geometric_mean(speedups);
  s.vs_native_median = median(vs_native);
  s.vs_native_geomean = geometric_mean(vs_native);
  return s;
}

nlohmann::json tune_report_json(const TuneOptions& o, const std::string& objective,
                                const std::string& scheduler, const std::string& size,
                                const TuneReport& report) {
  nlohmann::json cams = nlohmann::json::array();
  for (const auto& c : report.cameras)
    cams.push_back({{"camera", c.camera},
                    {"mode", c.mode},
                    {"frames", c.frames},
                    {"default_ms", c.default_ms},
                    {"chosen_ms", c.chosen_ms},
                    {"native_ms", c.native_ms},
                    {"speedup", c.speedup()},
                    {"speedup_ci95", {c.speedup_low, c.speedup_high}},
                    {"vs_native", c.vs_native()},
                    {"vs_native_ci95", {c.vs_native_low, c.vs_native_high}},
                    {"compare_rounds", c.compare_rounds},
                    {"compare_within_target", c.compare_within_target},
                    {"accumulated_ms", c.accumulated_ms},
                    {"race_candidates", c.race_candidates},
                    {"race_frames", c.race_frames},
                    {"race_changed_choice", c.race_changed_choice},
                    {"backend", c.backend},
                    {"config", c.config},
                    {"fallback", c.fallback},
                    {"rejected", c.rejected},
                    {"rejected_vs_native", c.rejected_vs_native},
                    {"rejected_speedup", c.rejected_speedup},
                    {"converged", c.converged}});
  TuneSummary s = summarize_tune(report);
  return {{"scene", o.scene},
          {"objective", objective},
          {"scheduler", scheduler},
          {"native_in_space", o.native_in_space},
          {"work_sizes", o.work_sizes},
          {"tuning_key", tuning_key(o)},
          {"size", size},
          {"spp", o.spp},
          {"iterations", o.iterations},
          {"baseline_repeats", o.baseline_repeats},
          {"finalists", o.finalists},
          {"race_rounds", o.race_rounds},
          {"compare_max_rounds", o.compare_max_rounds},
          {"compare_target", o.compare_target},
          {"cameras", cams},
          {"failed_builds", report.failed_builds},
          {"race",
           {{"changed_choice", s.race_changed},
            {"frames", s.race_frames},
            {"search_frames", s.search_frames}}},
          {"fallbacks", s.fallbacks},
          {"speedup", {{"median", s.speedup_median}, {"geomean", s.speedup_geomean}}},
          {"vs_native", {{"median", s.vs_native_median}, {"geomean", s.vs_native_geomean}}}};
}

}  // namespace tuneray
