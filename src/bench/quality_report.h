// What `bench quality` writes besides its table: the JSON report, the gnuplot data and script,
// and the per-scene ratio matrices with their geometric means.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "bench/quality_bench.h"

namespace tuneray {

// The report's header fields; the scenes go into its "scenes" array.
nlohmann::ordered_json quality_report_json(const QualityBenchOptions& options, int threads);
nlohmann::ordered_json quality_scene_json(const QualityScene& scene);

// Appends one data block per row (RMSE against time), in row order, for the plot script.
void append_plot_data(std::ostream& out, const QualityScene& scene);
// PREFIX.gp: one panel per scene, a line per row; block numbers count the rows of every scene
// before it in the data file.
void write_plot_script(const std::string& prefix, const std::vector<QualityScene>& scenes);

// One row per scene, one column per configuration other than the baseline (in order of first
// appearance): the row's `field` over the baseline's. A cell is empty without a baseline (or
// with a non-positive one) or when the scene did not run the configuration. `geo_means` is the
// geometric mean of each column's cells that are present.
struct RatioMatrix {
  struct Row {
    std::string scene;
    std::vector<std::optional<double>> cells;
  };
  std::vector<std::string> columns;
  std::vector<Row> rows;
  std::vector<std::optional<double>> geo_means;
};
RatioMatrix ratio_matrix(const std::vector<QualityScene>& scenes, double QualityRow::*field);

}  // namespace tuneray
