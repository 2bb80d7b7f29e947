// How long the tuner takes to decide: suggest() + report() with a tuning database that already
// holds 50,000 samples (500 states x 100 samples) of the renderer's BVH space and 8 indicators.
// Includes the SQLite transaction of every report (WAL, synchronous=NORMAL).
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "tuner/hybrid_tuner.h"
#include "tuner/latin_hypercube.h"

namespace tuneray::tuner {
namespace {

constexpr int kStates = 500;
constexpr int kSamplesPerState = 100;

Space bvh_space() {
  Space space;
  space.add_enum("quality", {"low", "medium", "high"}, "medium")
      .add_int_set("branching", {2, 4, 8}, 2)
      .add_int("max_depth", 8, 64, 32)
      .add_int_set("sah_block_size", {1, 2, 4, 8, 16}, 1)
      .add_int("min_leaf", 1, 8, 1)
      .add_int("max_leaf", 1, 32, 32)
      .add_real("cost_ratio", 0.05, 20.0, 1.0, Scale::kLog)
      .add_bool("static", false)
      .add_bool("compact", false)
      .add_bool("robust", false);
  space.add_constraint("min_leaf <= max_leaf", [](const Config& c) {
    return c.get_int("min_leaf") <= c.get_int("max_leaf");
  });
  space.add_condition("sah_block_size", Space::when_enum_not("quality", {"low"}));
  space.add_condition("cost_ratio", Space::when_enum_not("quality", {"low"}));
  return space;
}

IndicatorSchema schema() {
  IndicatorSchema s;
  for (int i = 0; i < 8; ++i) s.add("indicator" + std::to_string(i), 0.0, 1.0);
  return s;
}

double synthetic_cost(const std::vector<double>& state, const std::vector<double>& point) {
  double sum = 1.0;
  for (size_t i = 0; i < point.size(); ++i) {
    const double d = point[i] - state[i % state.size()];
    sum += d * d;
  }
  return sum;
}

std::string make_database() {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("tuner_bench_" + std::to_string(getpid()) + ".db"))
          .string();
  for (const char* suffix : {"", "-wal", "-shm"}) std::remove((path + suffix).c_str());
  const Space space = bvh_space();
  const IndicatorSchema indicators = schema();
  TuningDb db(path);
  const int64_t signature =
      db.open_signature("bench", "bench-cpu", space.describe(), indicators.describe());
  Rng rng(1);
  TuningDb::Transaction transaction(db);
  for (const auto& state : latin_hypercube(kStates, indicators.size(), rng)) {
    const int64_t state_id = db.add_state(signature, state);
    for (auto& point : latin_hypercube(kSamplesPerState, space.size(), rng)) {
      const Config config = space.feasible(point);
      db.add_sample(signature, state_id, db.config_id(signature, config.to_string()),
                    synthetic_cost(state, point), {});
    }
  }
  transaction.commit();
  return path;
}

TunerOptions options(const std::string& path, double epsilon, int replays = -1) {
  TunerOptions o;
  if (replays >= 0) o.gq.replays_per_sample = replays;
  o.db_path = path;
  o.tuning_key = "bench";
  o.hardware = "bench-cpu";
  o.epsilon = epsilon;
  return o;
}

// One state for many frames (the common case): suggest + report only. `replays`: the RBF
// predictor's replays per report (-1: the default), to show what they cost.
void BM_SuggestReportSameState(benchmark::State& bench, double epsilon, int replays) {
  const std::string path = make_database();
  {
    HybridTuner tuner(bvh_space(), schema(), options(path, epsilon, replays));
    const State state(8, 0.37);
    const Space& space = tuner.space();
    for (auto _ : bench) {
      const Config c = tuner.suggest(state);
      tuner.report(c, synthetic_cost(state, space.encode(c)), {{"build_ms", 1.0}});
    }
  }
  for (const char* suffix : {"", "-wal", "-shm"}) std::remove((path + suffix).c_str());
}

// A new state every frame: adds the state change (state lookup, prediction over the known
// states and candidates, policy decision) to every decision.
void BM_SuggestReportNewStateEveryCall(benchmark::State& bench) {
  const std::string path = make_database();
  {
    HybridTuner tuner(bvh_space(), schema(), options(path, 0.0));
    const Space& space = tuner.space();
    Rng rng(7);
    for (auto _ : bench) {
      State state(8);
      for (double& v : state) v = rng.uniform();
      const Config c = tuner.suggest(state);
      tuner.report(c, synthetic_cost(state, space.encode(c)));
    }
  }
  for (const char* suffix : {"", "-wal", "-shm"}) std::remove((path + suffix).c_str());
}

void BM_OpenDatabaseWith50kSamples(benchmark::State& bench) {
  const std::string path = make_database();
  for (auto _ : bench) {
    HybridTuner tuner(bvh_space(), schema(), options(path, 0.1));
    benchmark::DoNotOptimize(tuner.state_count());
  }
  for (const char* suffix : {"", "-wal", "-shm"}) std::remove((path + suffix).c_str());
}

BENCHMARK_CAPTURE(BM_SuggestReportSameState, search, 1.0, -1)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SuggestReportSameState, exploit, 0.0, -1)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SuggestReportSameState, exploit_no_replay, 0.0, 0)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SuggestReportSameState, exploit_32_replays, 0.0, 32)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SuggestReportNewStateEveryCall)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_OpenDatabaseWith50kSamples)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
}  // namespace tuneray::tuner

BENCHMARK_MAIN();
