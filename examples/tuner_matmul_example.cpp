// Tunes the block sizes of a blocked matrix multiply whose best blocking depends on the matrix
// size, given to the tuner as its only indicator.
//
//   1. Training: for a few sizes the tuner searches (epsilon = 1).
//   2. Unseen sizes: with epsilon = 0 the tuner predicts a blocking without searching; we compare
//      its time with the default blocking and with the best configuration a dedicated search
//      finds for that size.
//
// Usage: tuner_matmul_example [database.db]   (with a database, a second run resumes: the
// training sizes are already known and are not searched again).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "tuner/hybrid_tuner.h"

namespace {

using tuneray::tuner::Config;
using tuneray::tuner::HybridTuner;
using tuneray::tuner::IndicatorSchema;
using tuneray::tuner::PredictorKind;
using tuneray::tuner::Space;
using tuneray::tuner::State;
using tuneray::tuner::TunerOptions;

struct Matrices {
  explicit Matrices(int n) : n(n), a(n * n), b(n * n), c(n * n) {
    for (int i = 0; i < n * n; ++i) {
      a[i] = static_cast<float>((i * 7) % 13) * 0.1f;
      b[i] = static_cast<float>((i * 5) % 11) * 0.1f;
    }
  }
  int n;
  std::vector<float> a, b, c;
};

// C = A B with (bi x bk) blocks of A against (bk x bj) blocks of B; the innermost loop runs
// along rows of B and C so that it vectorises.
void blocked_multiply(Matrices& m, int bi, int bj, int bk) {
  const int n = m.n;
  std::fill(m.c.begin(), m.c.end(), 0.0f);
  for (int ii = 0; ii < n; ii += bi) {
    for (int kk = 0; kk < n; kk += bk) {
      for (int jj = 0; jj < n; jj += bj) {
        const int i_end = std::min(ii + bi, n);
        const int k_end = std::min(kk + bk, n);
        const int j_end = std::min(jj + bj, n);
        for (int i = ii; i < i_end; ++i) {
          float* __restrict c_row = &m.c[i * n];
          for (int k = kk; k < k_end; ++k) {
            const float a_ik = m.a[i * n + k];
            const float* __restrict b_row = &m.b[k * n];
            for (int j = jj; j < j_end; ++j) c_row[j] += a_ik * b_row[j];
          }
        }
      }
    }
  }
}

double seconds_for(Matrices& m, const Config& c) {
  const auto start = std::chrono::steady_clock::now();
  blocked_multiply(m, static_cast<int>(c.get_int("block_i")),
                   static_cast<int>(c.get_int("block_j")), static_cast<int>(c.get_int("block_k")));
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Space matmul_space() {
  Space space;
  const std::vector<int64_t> blocks = {4, 8, 16, 32, 64, 128, 256};
  space.add_int_set("block_i", blocks, 16).add_int_set("block_j", blocks, 16);
  space.add_int_set("block_k", blocks, 16);
  return space;
}

IndicatorSchema matmul_schema() {
  IndicatorSchema schema;
  schema.add("n", 0, 512);
  return schema;
}

TunerOptions options(double epsilon, const std::string& db_path) {
  TunerOptions o;
  o.epsilon = epsilon;
  o.predictor = PredictorKind::kBoth;
  o.search.max_iterations = 25;
  o.search.max_repeats = 2;
  o.db_path = db_path;
  o.tuning_key = "examples/matmul";
  return o;
}

// Runs the tuner on size n until it has settled (search finished or prediction made) and a few
// more frames; returns the median time of the configuration it settled on.
Config settle(HybridTuner& tuner, int n, int max_frames) {
  Matrices m(n);
  const State state{static_cast<double>(n)};
  for (int frame = 0; frame < max_frames; ++frame) {
    const Config c = tuner.suggest(state);
    tuner.report(c, seconds_for(m, c));
    if (tuner.mode() == tuneray::tuner::TunerMode::kExploit) break;
  }
  return tuner.suggest(state);
}

double median_seconds(int n, const Config& c) {
  Matrices m(n);
  std::vector<double> times;
  for (int i = 0; i < 5; ++i) times.push_back(seconds_for(m, c));
  std::sort(times.begin(), times.end());
  return times[2];
}

}  // namespace

int main(int argc, char** argv) {
  const std::string db_path = argc > 1 ? argv[1] : "";
  HybridTuner tuner(matmul_space(), matmul_schema(), options(1.0, db_path));

  std::printf("training sizes (searched):\n");
  for (int n : {64, 160, 256, 352, 448}) {
    const Config best = settle(tuner, n, 400);
    const auto summary = tuner.summary(State{static_cast<double>(n)});
    std::printf("  n=%3d  best %-40s %7.3f ms  (%d iterations, %zu measurements%s)\n", n,
                best.to_string().c_str(), 1e3 * median_seconds(n, best), summary->search_iterations,
                summary->samples, summary->converged ? ", converged" : "");
  }

  tuner.set_epsilon(0.0);
  std::printf("\nunseen sizes (predicted, no search):\n");
  std::printf("  %5s %10s %10s %10s   %s\n", "n", "default ms", "predict ms", "search ms",
              "predicted / searched");
  for (int n : {112, 208, 300, 400}) {
    const Config predicted = settle(tuner, n, 1);
    // Reference: a dedicated search for this size in a separate tuner.
    HybridTuner reference(matmul_space(), matmul_schema(), options(1.0, ""));
    const Config searched = settle(reference, n, 400);
    const double t_default = median_seconds(n, matmul_space().default_config());
    const double t_predicted = median_seconds(n, predicted);
    const double t_searched = median_seconds(n, searched);
    std::printf("  %5d %10.3f %10.3f %10.3f   %.2f  (%s)\n", n, 1e3 * t_default, 1e3 * t_predicted,
                1e3 * t_searched, t_predicted / t_searched, predicted.to_string().c_str());
  }
  return 0;
}
