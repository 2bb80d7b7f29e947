// tuneray bench quality: the ablation of bench/quality_bench.h, printed as it runs, with its
// JSON report, gnuplot files and ratio matrices.
#include <fmt/core.h>
#include <tbb/task_arena.h>

#include <filesystem>
#include <fstream>
#include <memory>

#include "app/commands.h"
#include "app/progress.h"
#include "bench/quality_report.h"
#include "bench/scene_paths.h"
#include "image/atomic_file.h"

namespace tuneray {

namespace {

const char* kHeader = "{:<11} {:>8} {:>7} {:>7} {:>7} {:>7} {:>6} {:>6} {:>9} {:>7} {:>7} {:>8}\n";

void print_row(const QualityRow& r) {
  std::string ratio = r.baseline_rmse > 0 ? fmt::format("{:.3f}", r.rmse_vs_baseline()) : "-";
  std::string exact =
      r.exact_baseline_rmse > 0 ? fmt::format("{:.3f}", r.exact_rmse_vs_baseline()) : "-";
  fmt::print(fmt::runtime(kHeader), r.name, fmt::format("{:.2f}", r.ms_per_spp),
             fmt::format("{:.2f}", r.intersect), fmt::format("{:.2f}", r.shading),
             fmt::format("{:.2f}", r.shadow), fmt::format("{:.2f}", r.mrays_per_s),
             fmt::format("{:.1f}", r.spp.back()), fmt::format("{:.2f}", r.time_over_budget),
             fmt::format("{:.5f}", r.rmse_at_budget), ratio, exact, fmt::format("{:.5f}", r.bias));
  std::fflush(stdout);
}

using BarSlot = std::shared_ptr<std::unique_ptr<ProgressBar>>;

// The truth's progress bar lives from the truth's first pass to the `ready` hook.
QualityHooks printing_hooks(const QualityBenchOptions& a, BarSlot bar) {
  QualityHooks h;
  h.loaded = [](const QualityScene& s) {
    fmt::print("{}: {} triangles, one-texel {} of {} candidates\n", s.name, s.triangles,
               s.one_texel_collapsed, s.one_texel_candidates);
    std::fflush(stdout);
  };
  h.truth_progress = [a, bar](int spp, double estimate) {
    if (!*bar) *bar = std::make_unique<ProgressBar>("truth", a.truth_spp, stderr_is_terminal());
    (*bar)->advance(static_cast<uint64_t>(spp));
    if (estimate >= 0) (*bar)->set_suffix("est. RMSE " + std::to_string(estimate));
  };
  h.ready = [a, bar](const QualityScene& s) {
    bar->reset();
    if (s.truth.rendered)
      fmt::print("truth {} (rendered: {} spp in {:.1f} s, estimated RMSE {:.5f})\n", s.truth_path,
                 s.truth.spp, s.truth.render_ms / 1e3, s.truth.estimated_rmse);
    else
      fmt::print("truth {} (cached)\n", s.truth_path);
    fmt::print("the truth's own noise: RMSE {:.5f} against the exact image (from its halves)\n",
               s.truth_noise_rmse);
    fmt::print("frame budget {:.1f} ms, {} frames\n", s.frame_ms, a.frames);
    fmt::print(fmt::runtime(kHeader), "config", "ms/spp", "isect", "shade", "shadow", "Mray/s",
               "spp", "t/T", "RMSE@T", "vs base", "exact", "bias");
    std::fflush(stdout);
  };
  h.repeat_done = [a](const QualityScene& s, int rep) {
    fmt::print(stderr, "{}: repeat {}/{} done\n", s.name, rep + 1, a.repeats);
    std::fflush(stderr);
  };
  h.row = print_row;
  h.sweep = [](const SweepPoint& p) {
    fmt::print("sweep {} {:>5}: {:.2f} ms/spp\n", p.mode == "tile" ? "tile" : "batch", p.size,
               p.ms_per_spp);
  };
  return h;
}

// Markdown: one row per scene, one column per configuration, and the geometric means.
void print_ratio_matrix(const std::string& title, const RatioMatrix& m) {
  if (m.columns.empty()) return;
  auto cell = [](const std::optional<double>& v) {
    return v ? fmt::format(" {:.2f} |", *v) : std::string(" - |");
  };
  fmt::print("\n{}\n\n| scene |", title);
  for (const std::string& n : m.columns) fmt::print(" {} |", n);
  fmt::print("\n|---|");
  for (size_t i = 0; i < m.columns.size(); ++i) fmt::print("---|");
  fmt::print("\n");
  for (const RatioMatrix::Row& row : m.rows) {
    fmt::print("| {} |", row.scene);
    for (const auto& c : row.cells) fmt::print("{}", cell(c));
    fmt::print("\n");
  }
  fmt::print("| geo-mean |");
  for (const auto& g : m.geo_means) fmt::print("{}", cell(g));
  fmt::print("\n");
}

void create_parent(const std::string& path) {
  std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
}

}  // namespace

int run_bench_quality(const QualityBenchOptions& a) {
  std::vector<std::string> specs = a.scenes.empty() ? all_scene_json_files() : a.scenes;
  if (specs.empty()) throw std::invalid_argument("bench quality: no scenes given or found");
  nlohmann::ordered_json out = quality_report_json(a, tbb::this_task_arena::max_concurrency());
  if (!a.plot.empty()) create_parent(a.plot);
  std::vector<QualityScene> scenes;
  for (const std::string& spec : specs) {
    BarSlot bar = std::make_shared<std::unique_ptr<ProgressBar>>();
    scenes.push_back(run_quality_scene(a, spec, printing_hooks(a, bar)));
    out["scenes"].push_back(quality_scene_json(scenes.back()));
    // Rewritten whole after every scene, so an interrupted run keeps what it measured.
    if (!a.plot.empty()) {
      ReplacingFile plot_data(a.plot + ".dat");
      for (const QualityScene& s : scenes) append_plot_data(plot_data.stream(), s);
      plot_data.commit();
    }
    if (!a.json.empty()) {
      create_parent(a.json);
      write_text_file(a.json, out.dump(2) + "\n");
    }
    fmt::print("\n");
  }
  if (!a.plot.empty()) write_plot_script(a.plot, scenes);
  print_ratio_matrix(
      "RMSE at equal time (frames x budget) / baseline's (median over repeats), against the "
      "exact image (the truth's own noise taken off both):",
      ratio_matrix(scenes, &QualityRow::exact_rmse_at_budget));
  print_ratio_matrix("The same as measured against the truth (its noise included):",
                     ratio_matrix(scenes, &QualityRow::rmse_at_budget));
  print_ratio_matrix("Time per spp / baseline's:", ratio_matrix(scenes, &QualityRow::ms_per_spp));
  return 0;
}

}  // namespace tuneray
