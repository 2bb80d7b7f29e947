#include "tuning/eval_figures.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "common/temp_dir.h"

namespace tuneray {
namespace {

std::string read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

CameraRecord camera(int index, std::vector<double> search_ms, double default_ms, double native_ms) {
  CameraRecord c;
  c.scene = "box";
  c.objective = "render";
  c.camera = index;
  c.search_ms = std::move(search_ms);
  c.default_ms = default_ms;
  c.converged_ms = default_ms / 1.25;
  c.native_ms = native_ms;
  return c;
}

PredictionRecord prediction(int repetition, int camera, const char* predictor, double ms) {
  PredictionRecord p;
  p.scene = "box";
  p.objective = "render";
  p.repetition = repetition;
  p.camera = camera;
  p.predictor = predictor;
  p.predicted_ms = ms;
  p.speedup = 1.1;
  p.roofline = {0.9, 0.85, 0.95};
  p.break_even = 3;
  return p;
}

EvalResults two_cameras() {
  EvalResults r;
  // Out of path order on purpose: the trace follows the camera index.
  r.cameras = {camera(1, {5, 4}, 6, 3.5), camera(0, {2, 3, 1.5}, 2.5, 0)};
  r.predictions = {prediction(0, 1, "nn", 4.25), prediction(0, 1, "rbf", 4.5),
                   // Another repetition's choice for camera 0: not in the trace.
                   prediction(1, 0, "nn", 9)};
  return r;
}

TEST(EvalFigures, TraceFollowsThePathWithComparedCostsAndRepetitionZerosPredictions) {
  testing::TempDir dir;
  const EvalResults r = two_cameras();
  write_eval_figures(r, summarise(r), dir.path());
  EXPECT_EQ(read_all(dir.file("trace_box_render.dat")),
            "# frame search_ms default_ms native_ms nn_ms rbf_ms (? = none)\n"
            "0 2.000 2.500 ? ? ?\n"
            "1 3.000 2.500 ? ? ?\n"
            "2 1.500 2.500 ? ? ?\n"
            "\n"
            "3 5.000 6.000 3.500 4.250 4.500\n"
            "4 4.000 6.000 3.500 4.250 4.500\n"
            "\n");
  const std::string script = read_all(dir.file("trace_box_render.png.gp"));
  EXPECT_NE(script.find("set datafile missing '?'"), std::string::npos);
  EXPECT_NE(script.find("title 'native Embree'"), std::string::npos);
}

TEST(EvalFigures, PublishedValuesAreMarkedPerObjective) {
  testing::TempDir dir;
  EvalResults r = two_cameras();
  for (CameraRecord c : two_cameras().cameras) {
    c.objective = "total";
    r.cameras.push_back(c);
  }
  for (PredictionRecord p : two_cameras().predictions) {
    p.objective = "total";
    r.predictions.push_back(p);
  }
  write_eval_figures(r, summarise(r), dir.path());
  const std::string render_predictors = read_all(dir.file("predictor_speedup_render.svg.gp"));
  EXPECT_NE(render_predictors.find(", 1.05 with lines dt 2"), std::string::npos);
  EXPECT_NE(render_predictors.find(", 1.04 with lines dt 2"), std::string::npos);
  const std::string total_predictors = read_all(dir.file("predictor_speedup_total.svg.gp"));
  EXPECT_NE(total_predictors.find(", 1.12 with lines dt 2"), std::string::npos);
  EXPECT_EQ(total_predictors.find("published RBF"), std::string::npos);  // none published
  const std::string total_roofline = read_all(dir.file("roofline_total.png.gp"));
  EXPECT_NE(total_roofline.find(", 0.92 with lines"), std::string::npos);
  EXPECT_NE(total_roofline.find(", 0.83 with lines"), std::string::npos);
  EXPECT_NE(read_all(dir.file("search_speedup_render.png.gp")).find(", 1.04 with lines dt 2"),
            std::string::npos);
}

TEST(EvalFigures, PublishedValuesOfTheTwoObjectives) {
  const PublishedValues render = published_values("render");
  EXPECT_EQ(render.nn_speedup, 1.05);
  EXPECT_EQ(render.rbf_roofline, 0.95);
  const PublishedValues total = published_values("total");
  EXPECT_EQ(total.nn_speedup, 1.12);
  EXPECT_EQ(total.rbf_speedup, 0.0);
  EXPECT_EQ(total.rbf_roofline, 0.83);
  EXPECT_EQ(published_values("other").nn_roofline, 0.0);
}

TEST(EvalFigures, TraceStemsAreSafeFileNames) {
  EXPECT_EQ(trace_figure_stem("scenes/a b.json", "total"), "trace_scenes_a_b_json_total");
  EXPECT_EQ(trace_figure_stem("lost-empire", "render"), "trace_lost-empire_render");
}

}  // namespace
}  // namespace tuneray
