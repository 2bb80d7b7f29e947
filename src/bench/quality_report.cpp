#include "bench/quality_report.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "image/atomic_file.h"
#include "tuning/stats.h"

namespace tuneray {

nlohmann::ordered_json quality_report_json(const QualityBenchOptions& a, int threads) {
  return {{"size", std::to_string(a.width) + "x" + std::to_string(a.height)},
          {"frame_ms", a.frame_ms},
          {"frames", a.frames},
          {"repeats", a.repeats},
          {"target_spp", a.target_spp},
          {"max_bounces", a.max_bounces},
          {"clamp", a.clamp},
          {"clamp_relative", a.clamp_relative},
          {"truth_spp", a.truth_spp},
          {"truth_until_rmse", a.truth_until_rmse},
          {"threads", threads},
          {"scenes", nlohmann::ordered_json::array()}};
}

nlohmann::ordered_json quality_scene_json(const QualityScene& scene) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const QualityRow& r : scene.rows)
    rows.push_back({{"config", r.name},
                    {"ms_per_spp", r.ms_per_spp},
                    {"intersect_ms_per_spp", r.intersect},
                    {"shading_ms_per_spp", r.shading},
                    {"shadow_ms_per_spp", r.shadow},
                    {"mrays_per_s", r.mrays_per_s},
                    {"spp", r.spp},
                    {"time_ms", r.time_ms},
                    {"rmse", r.rmse},
                    {"rmse_repeats", r.rmse_repeats},
                    {"rmse_at_budget", r.rmse_at_budget},
                    {"time_over_budget", r.time_over_budget},
                    {"rmse_vs_baseline", r.rmse_vs_baseline()},
                    {"exact_rmse_at_budget", r.exact_rmse_at_budget},
                    {"exact_rmse_vs_baseline", r.exact_rmse_vs_baseline()},
                    {"bias", r.bias}});
  nlohmann::ordered_json sweep = nlohmann::ordered_json::array();
  for (const SweepPoint& p : scene.sweep)
    sweep.push_back({{"mode", p.mode}, {"size", p.size}, {"ms_per_spp", p.ms_per_spp}});
  return {{"scene", scene.spec},
          {"name", scene.name},
          {"triangles", scene.triangles},
          {"one_texel_candidates", scene.one_texel_candidates},
          {"one_texel_collapsed", scene.one_texel_collapsed},
          {"truth", scene.truth_path},
          {"truth_spp", scene.truth_spp},
          {"truth_noise_rmse", scene.truth_noise_rmse},
          {"frame_ms", scene.frame_ms},
          {"configs", rows},
          {"sweep", sweep}};
}

void append_plot_data(std::ostream& out, const QualityScene& scene) {
  for (const QualityRow& r : scene.rows) {
    out << "\"" << scene.name << " " << r.name << "\"\n";
    for (size_t f = 0; f < r.time_ms.size(); ++f) out << r.time_ms[f] << " " << r.rmse[f] << "\n";
    out << "\n\n";
  }
}

void write_plot_script(const std::string& prefix, const std::vector<QualityScene>& scenes) {
  ReplacingFile gp(prefix + ".gp");
  std::string data = std::filesystem::path(prefix + ".dat").filename().string();
  const int cols = scenes.size() > 1 ? 2 : 1;
  const int rows = static_cast<int>((scenes.size() + cols - 1) / cols);
  gp << "# gnuplot " << std::filesystem::path(prefix + ".gp").filename().string()
     << ": RMSE against the ground truth vs time, one panel per scene\n"
     << "set terminal pngcairo size " << 700 * cols << "," << 420 * rows << " font ',9'\n"
     << "set output '" << std::filesystem::path(prefix + ".png").filename().string() << "'\n"
     << "set multiplot layout " << rows << "," << cols << "\n"
     << "set xlabel 'time (ms)'\nset ylabel 'RMSE'\nset logscale y\nset key outside right\n";
  int block = 0;
  for (const QualityScene& scene : scenes) {
    gp << "set title '" << scene.name << "'\nplot ";
    for (size_t i = 0; i < scene.rows.size(); ++i)
      gp << (i ? ", \\\n     " : "") << "'" << data << "' index " << block++
         << " using 1:2 with linespoints title '" << scene.rows[i].name << "'";
    gp << "\n";
  }
  gp << "unset multiplot\n";
  gp.commit();
}

RatioMatrix ratio_matrix(const std::vector<QualityScene>& scenes, double QualityRow::*field) {
  RatioMatrix m;
  for (const QualityScene& scene : scenes)
    for (const QualityRow& r : scene.rows)
      if (r.name != "baseline" &&
          std::find(m.columns.begin(), m.columns.end(), r.name) == m.columns.end())
        m.columns.push_back(r.name);
  std::vector<std::vector<double>> ratios(m.columns.size());
  for (const QualityScene& scene : scenes) {
    double base = 0;
    for (const QualityRow& r : scene.rows)
      if (r.name == "baseline") base = r.*field;
    RatioMatrix::Row row{scene.name, std::vector<std::optional<double>>(m.columns.size())};
    for (size_t i = 0; i < m.columns.size(); ++i)
      for (const QualityRow& r : scene.rows) {
        if (r.name != m.columns[i] || !(base > 0)) continue;
        ratios[i].push_back(r.*field / base);
        row.cells[i] = ratios[i].back();
      }
    m.rows.push_back(row);
  }
  for (const std::vector<double>& r : ratios)
    m.geo_means.push_back(r.empty() ? std::nullopt : std::optional(geometric_mean(r)));
  return m;
}

}  // namespace tuneray
