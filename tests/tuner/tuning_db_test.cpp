#include "tuner/tuning_db.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <iterator>
#include <sstream>

#include "synthetic_problem.h"
#include "temp_path.h"
#include "tuner/hardware_signature.h"
#include "tuner/hybrid_tuner.h"

namespace tuneray::tuner {
namespace {

using testing::kernel_cost;
using testing::kernel_schema;
using testing::kernel_space;
using testing::TempPath;

TunerOptions db_options(const std::string& path, uint64_t seed = 3) {
  TunerOptions options;
  options.db_path = path;
  options.hardware = "test-cpu x2";
  options.seed = seed;
  options.epsilon = 0.5;
  options.search.max_iterations = 25;
  return options;
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A deterministic but noisy cost, so that repeats and medians matter.
double noisy_cost(const State& state, const Config& c, int step) {
  return kernel_cost(state, c) * (1.0 + 0.03 * std::sin(step * 12.9898));
}

const std::vector<double> kSizes = {120, 480, 120, 820, 300, 480, 50, 820, 990, 300};

// Runs steps [first, last) of a fixed schedule (12 steps per state of kSizes, cycling).
std::vector<std::string> run_schedule(HybridTuner& tuner, int first, int last) {
  std::vector<std::string> suggested;
  for (int step = first; step < last; ++step) {
    const State state{kSizes[(step / 12) % kSizes.size()]};
    const Config c = tuner.suggest(state);
    suggested.push_back(c.to_string());
    if (c.get_int("block") == 128 && c.get_int("unroll") == 8) {
      tuner.report_failure(c);
    } else {
      tuner.report(c, noisy_cost(state, c, step), {{"build_ms", 0.5 * step}, {"render_ms", 2.0}});
    }
  }
  return suggested;
}

TEST(TuningDb, RoundTripOfSamplesStatesExtrasAndCsv) {
  TempPath path("roundtrip.db");
  {
    HybridTuner tuner(kernel_space(), kernel_schema(), db_options(path.str()));
    run_schedule(tuner, 0, 40);
  }
  TuningDb db(path.str());
  const auto signature = db.find_signature("default", "test-cpu x2");
  ASSERT_TRUE(signature);
  const auto samples = db.samples(*signature);
  ASSERT_EQ(samples.size(), 40u);
  EXPECT_EQ(db.states(*signature).size(), 3u);  // 120, 480, 120 again, 820 within 40 steps
  EXPECT_EQ(samples[3].extras.at("build_ms"), 1.5);
  EXPECT_EQ(samples[3].extras.at("render_ms"), 2.0);
  const Config c = kernel_space().parse(samples[3].config);
  EXPECT_DOUBLE_EQ(samples[3].cost, noisy_cost(State{120}, c, 3));
  std::ostringstream csv;
  db.export_csv(csv, *signature);
  const std::string text = csv.str();
  EXPECT_EQ(text.rfind("sample_id,tuning_key,hardware,state_id,indicators,config,cost,failed,"
                       "extras,time\n",
                       0),
            0u);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 41);
  EXPECT_NE(text.find("build_ms=1.5;render_ms=2.0"), std::string::npos);
}

TEST(TuningDb, ResumedTunerMakesTheSameSuggestionsAsAnUninterruptedOne) {
  TempPath straight_path("straight.db");
  TempPath resumed_path("resumed.db");
  std::vector<std::string> straight;
  {
    HybridTuner tuner(kernel_space(), kernel_schema(), db_options(straight_path.str()));
    straight = run_schedule(tuner, 0, 150);
  }
  std::vector<std::string> resumed;
  // Stop at several points, some in the middle of a search, and reopen each time.
  const int stops[] = {0, 17, 40, 41, 95, 150};
  bool stopped_mid_search = false;
  for (size_t i = 0; i + 1 < std::size(stops); ++i) {
    HybridTuner tuner(kernel_space(), kernel_schema(), db_options(resumed_path.str()));
    const auto part = run_schedule(tuner, stops[i], stops[i + 1]);
    resumed.insert(resumed.end(), part.begin(), part.end());
    for (const auto& s : tuner.summaries()) stopped_mid_search |= s.searching;
  }
  EXPECT_TRUE(stopped_mid_search);
  EXPECT_EQ(resumed, straight);
}

TEST(TuningDb, ThetaIsRebuiltFromSamplesAfterTheSnapshot) {
  TempPath path("snapshot.db");
  TunerOptions options = db_options(path.str());
  options.model_snapshot_interval = 7;
  std::vector<double> theta;
  {
    HybridTuner tuner(kernel_space(), kernel_schema(), options);
    run_schedule(tuner, 0, 60);
    theta = tuner.gq().theta();
  }
  TuningDb db(path.str());
  const auto signature = db.find_signature("default", "test-cpu x2");
  const auto model = db.model(*signature);
  ASSERT_TRUE(model);
  EXPECT_EQ(model->first, 60);
  // As if the process had died after the snapshot at sample 21: fold only the first 21 samples
  // into a model, store it as the snapshot, and reopen: the other 39 must be replayed into θ.
  {
    TempPath scratch("snapshot_scratch.db");
    TunerOptions scratch_options = options;
    scratch_options.db_path = scratch.str();
    scratch_options.model_snapshot_interval = 1000000;
    HybridTuner partial(kernel_space(), kernel_schema(), scratch_options);
    run_schedule(partial, 0, 21);
    db.put_model(*signature, 21, partial.gq().serialise());
  }
  HybridTuner reopened(kernel_space(), kernel_schema(), options);
  EXPECT_EQ(reopened.gq().theta(), theta);
}

TEST(TuningDb, TuningKeysShareAFileWithoutMixing) {
  TempPath path("keys.db");
  TunerOptions render = db_options(path.str());
  render.tuning_key = "bvh/render";
  TunerOptions total = db_options(path.str());
  total.tuning_key = "bvh/total";
  {
    HybridTuner a(kernel_space(), kernel_schema(), render);
    run_schedule(a, 0, 10);
    HybridTuner b(kernel_space(), kernel_schema(), total);
    run_schedule(b, 0, 3);
  }
  TuningDb db(path.str());
  EXPECT_EQ(db.samples(*db.find_signature("bvh/render", "test-cpu x2")).size(), 10u);
  EXPECT_EQ(db.samples(*db.find_signature("bvh/total", "test-cpu x2")).size(), 3u);
  // The same key with another space is refused, not mixed.
  Space other = kernel_space();
  other.add_bool("prefetch", false);
  EXPECT_THROW(HybridTuner(other, kernel_schema(), render), TuningDbError);
}

TEST(TuningDb, ListsTheMachinesThatRecordedSamplesOfAKey) {
  TempPath path("machines.db");
  TunerOptions here = db_options(path.str());
  TunerOptions there = db_options(path.str());
  there.hardware = "other-cpu x64";
  TunerOptions idle = db_options(path.str());
  idle.hardware = "idle-cpu x1";
  {
    HybridTuner a(kernel_space(), kernel_schema(), here);
    run_schedule(a, 0, 4);
    HybridTuner b(kernel_space(), kernel_schema(), there);
    run_schedule(b, 0, 2);
    HybridTuner c(kernel_space(), kernel_schema(), idle);  // opened, never reported
  }
  TuningDb db(path.str());
  const auto rows = db.hardware_with_samples(here.tuning_key);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].hardware, "test-cpu x2");
  EXPECT_EQ(rows[0].samples, 4);
  EXPECT_EQ(rows[1].hardware, "other-cpu x64");
  EXPECT_EQ(rows[1].samples, 2);
  EXPECT_TRUE(db.hardware_with_samples("no/such/key").empty());
}

TEST(TuningDb, RefusesForeignAndCorruptFilesWithoutTouchingThem) {
  TempPath text_file("not_a_db.txt");
  {
    std::ofstream out(text_file.str());
    out << "this is a text file, not a tuning database\n" << std::string(4096, 'x');
  }
  const std::string text_before = file_bytes(text_file.str());
  EXPECT_THROW(TuningDb{text_file.str()}, TuningDbError);
  EXPECT_EQ(file_bytes(text_file.str()), text_before);

  TempPath foreign("foreign.db");
  {
    sqlite3* raw = nullptr;
    ASSERT_EQ(sqlite3_open(foreign.str().c_str(), &raw), SQLITE_OK);
    sqlite3_exec(raw, "CREATE TABLE songs(title TEXT); INSERT INTO songs VALUES('x');", nullptr,
                 nullptr, nullptr);
    sqlite3_close(raw);
  }
  const std::string foreign_before = file_bytes(foreign.str());
  try {
    TuningDb db(foreign.str());
    FAIL() << "a foreign database was accepted";
  } catch (const TuningDbError& e) {
    EXPECT_NE(std::string(e.what()).find("another program"), std::string::npos) << e.what();
  }
  EXPECT_EQ(file_bytes(foreign.str()), foreign_before);

  TempPath newer("newer.db");
  { TuningDb db(newer.str()); }
  {
    sqlite3* raw = nullptr;
    ASSERT_EQ(sqlite3_open(newer.str().c_str(), &raw), SQLITE_OK);
    sqlite3_exec(raw, "UPDATE meta SET value='99' WHERE key='schema_version'", nullptr, nullptr,
                 nullptr);
    sqlite3_close(raw);
  }
  EXPECT_THROW(TuningDb{newer.str()}, TuningDbError);

  TempPath corrupt("corrupt.db");
  {
    HybridTuner tuner(kernel_space(), kernel_schema(), db_options(corrupt.str()));
    run_schedule(tuner, 0, 30);
  }
  {
    // Overwrite the middle of the file (the page headers) with garbage.
    std::fstream f(corrupt.str(), std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(100);
    const std::string garbage(8000, '\x5a');
    f.write(garbage.data(), static_cast<std::streamsize>(garbage.size()));
  }
  EXPECT_THROW(HybridTuner(kernel_space(), kernel_schema(), db_options(corrupt.str())),
               TuningDbError);
}

// A child process reports in a loop and tells the parent through a pipe after each report
// returned; the parent kills it with SIGKILL after a random delay. Every sample whose report
// returned must be in the database, which must open, and a tuner must continue from it.
TEST(TuningDb, SigkillWhileReportingLosesNoReturnedSample) {
  TempPath path("sigkill.db");
  Rng rng(2024);
  int64_t returned_total = 0;
  for (int round = 0; round < 5; ++round) {
    int fds[2];
    ASSERT_EQ(pipe(fds), 0);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      close(fds[0]);
      HybridTuner tuner(kernel_space(), kernel_schema(), db_options(path.str()));
      for (int step = 0;; ++step) {
        const State state{kSizes[(step / 12) % kSizes.size()]};
        const Config c = tuner.suggest(state);
        tuner.report(c, noisy_cost(state, c, step), {{"build_ms", 1.0}});
        const char done = 1;
        if (write(fds[1], &done, 1) != 1) _exit(1);
      }
    }
    close(fds[1]);
    usleep(static_cast<useconds_t>(10000 + rng.below(140000)));
    kill(child, SIGKILL);
    int status = 0;
    waitpid(child, &status, 0);
    EXPECT_TRUE(WIFSIGNALED(status));
    char buffer[4096];
    int64_t returned = 0;
    for (ssize_t n; (n = read(fds[0], buffer, sizeof buffer)) > 0;) returned += n;
    close(fds[0]);
    returned_total += returned;

    TuningDb db(path.str());
    // No signature yet when the first child was killed while creating the file.
    const auto signature = db.find_signature("default", "test-cpu x2");
    const auto stored = signature ? static_cast<int64_t>(db.samples(*signature).size()) : 0;
    // At most one more: killed after the commit but before telling the parent.
    EXPECT_GE(stored, returned_total) << "round " << round;
    EXPECT_LE(stored, returned_total + 1) << "round " << round;
    returned_total = stored;
  }
  EXPECT_GT(returned_total, 0);
  HybridTuner tuner(kernel_space(), kernel_schema(), db_options(path.str()));
  const Config c = tuner.suggest(State{500.0});
  EXPECT_NO_THROW(tuner.report(c, 1.0));
}

TEST(TuningDb, HardwareSignatureNamesCpuAndThreads) {
  const std::string signature = hardware_signature();
  EXPECT_FALSE(signature.empty());
  EXPECT_NE(signature.rfind(" x"), std::string::npos) << signature;
  EXPECT_EQ(signature, hardware_signature());
}

}  // namespace
}  // namespace tuneray::tuner
