// The study's figures (DESIGN §6, issue 12): gnuplot scripts and their data, drawn as PNG and
// SVG. Per objective: the converged search's speedup per scene (over the default configuration
// and over native Embree), the predictors' speedup over search, the roofline and the break-even
// frames; per scene and objective, the tuning trace along the camera path (every search frame,
// beside the default configuration, native Embree and both predictors). Where the paper
// published a value for a figure, the figure marks it.
#pragma once

#include <string>
#include <vector>

#include "tuning/eval_report.h"
#include "tuning/eval_study.h"

namespace tuneray {

// The paper's values (Herveau et al., DESIGN §6) that a figure marks; 0 = none published.
struct PublishedValues {
  double search_speedup = 0;  // converged search over the default, median of the other scenes
  double nn_speedup = 0;      // prediction over search, geo-mean
  double rbf_speedup = 0;
  double nn_roofline = 0;
  double rbf_roofline = 0;
};

// For "render" (progressive rendering) and "total" (build + render); zeros for anything else.
PublishedValues published_values(const std::string& objective);

// The file stem of a scene's tuning trace for one objective (scene names may hold characters
// that file names should not: they become '_').
std::string trace_figure_stem(const std::string& scene, const std::string& objective);

// Writes the data files and scripts into `dir` (existing files are replaced whole).
void write_eval_figures(const EvalResults& results, const std::vector<EvalSummary>& summaries,
                        const std::string& dir);

// Draws every script in `dir` with gnuplot, each image written aside and renamed. False when
// gnuplot is missing or any script failed.
bool draw_eval_figures(const std::string& dir);

}  // namespace tuneray
