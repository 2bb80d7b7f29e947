// `eval --synthetic-costs` killed with SIGKILL at random moments and resumed with the same
// command finishes with the same report as an uninterrupted run: the tuning database, the
// comparison log and the report files survive any kill, and a resumed study repeats no decision,
// counts no frame twice and measures a comparison cut short again whole. Synthetic costs make every
// run's numbers identical, so the final files are compared byte for byte.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <random>
#include <thread>

#include "command_test.h"
#include "report_files.h"
#include "run_command.h"

namespace tuneray {
namespace {

namespace fs = std::filesystem;
using testing::differences;
using testing::read_all;
using testing::report_files;
using Clock = std::chrono::steady_clock;
using Seconds = std::chrono::duration<double>;

struct Outcome {
  bool killed = false;  // by us, at the deadline
  bool signaled = false;
  int exit_code = -1;
  Seconds elapsed{0};
};

// Runs tuneray with `args` (output appended to `log`) and SIGKILLs it after `kill_after` unless
// it ended before.
Outcome run_killed_after(const std::vector<std::string>& args, Seconds kill_after,
                         const std::string& log) {
  std::string binary = testing::tuneray_binary();
  std::vector<std::string> copies = args;
  std::vector<char*> argv{binary.data()};
  for (std::string& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  const auto start = Clock::now();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (fd >= 0) {
      dup2(fd, STDOUT_FILENO);
      dup2(fd, STDERR_FILENO);
    }
    execv(binary.c_str(), argv.data());
    _exit(127);
  }
  Outcome outcome;
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (Clock::now() - start >= kill_after) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      outcome.killed = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  outcome.elapsed = Clock::now() - start;
  if (WIFSIGNALED(status))
    outcome.signaled = true;
  else
    outcome.exit_code = WEXITSTATUS(status);
  return outcome;
}

// A gnuplot orphaned by a kill may still be drawing into its own temporary file in `out`: retry
// until the folder is gone.
void remove_folder(const fs::path& out) {
  std::error_code ec;
  for (int attempt = 0; attempt < 100 && fs::exists(out); ++attempt) {
    fs::remove_all(out, ec);
    if (ec) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_FALSE(fs::exists(out)) << "cannot remove " << out << ": " << ec.message();
}

class EvalKill : public testing::CommandTest {
 protected:
  // One uninterrupted run, then `trials` runs each killed 1 to 3 times after random delays
  // (seeded, uniform over the uninterrupted run's duration) and resumed until one finishes.
  void check_kills(int trials, uint64_t seed) {
    // One folder for every run: report.md quotes the command, --out included. More cameras and
    // frames than the profile's put most of the run (and of the kills) in the study proper
    // rather than in gnuplot.
    const fs::path out = path("eval");
    const std::string log = path("log.txt");
    const std::vector<std::string> args = {
        "eval",   "--profile",  "quick",  "--synthetic-costs", "--objective",
        "render", "--cameras",  "10",     "--iterations",      "24",
        "--out",  out.string(), "--quiet"};
    const Outcome whole = run_killed_after(args, Seconds(600), log);
    ASSERT_FALSE(whole.signaled) << read_all(log);
    ASSERT_EQ(whole.exit_code, 0) << read_all(log);
    const auto reference = report_files(out);
    for (const char* name :
         {"report.md", "cameras.csv", "search_frames.csv", "predictions.csv", "summary.csv"})
      ASSERT_TRUE(reference.count(name)) << name;
    ASSERT_NE(reference.at("report.md").find("Synthetic costs"), std::string::npos);

    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> moment(0.0, whole.elapsed.count());
    int matched = 0, kills = 0, kills_in_study = 0;
    for (int trial = 0; trial < trials; ++trial) {
      remove_folder(out);
      const int planned_kills = 1 + static_cast<int>(rng() % 3);
      std::string history;
      for (int attempt = 0;; ++attempt) {
        ASSERT_LT(attempt, 20) << "trial " << trial << " never finished";
        const Seconds delay(attempt < planned_kills ? moment(rng) : 600.0);
        const Outcome o = run_killed_after(args, delay, log);
        if (o.killed) {
          ++kills;
          if (!fs::exists(out / "cameras.csv")) ++kills_in_study;
          history += " killed at " + std::to_string(o.elapsed.count()) + " s;";
          continue;
        }
        ASSERT_FALSE(o.signaled) << "trial " << trial << ": crashed after" << history << "\n"
                                 << read_all(log);
        ASSERT_EQ(o.exit_code, 0) << "trial " << trial << ":" << history << "\n" << read_all(log);
        break;
      }
      const std::string diff = differences(reference, report_files(out));
      EXPECT_TRUE(diff.empty()) << "trial " << trial << " (" << history
                                << ") differs from the uninterrupted run in:" << diff;
      matched += diff.empty() ? 1 : 0;
    }
    std::cout << "eval killed and resumed: " << matched << "/" << trials
              << " final reports identical to the uninterrupted run's (" << kills << " kills, "
              << kills_in_study << " of them during the study, before any report file; "
              << "uninterrupted run " << whole.elapsed.count() << " s)\n";
    EXPECT_EQ(matched, trials);
    // Planned kills land before the run ends (each delay is below its duration) unless the
    // machine happens to run much faster than during the uninterrupted run.
    EXPECT_GE(kills, trials / 2);
  }
};

TEST_F(EvalKill, KilledThreeTimesAndResumedGivesTheUninterruptedReport) {
  check_kills(3, 13);
}

TEST_F(EvalKill, KilledTwentyTimesAndResumedGivesTheUninterruptedReport) {
  check_kills(20, 2026);
}

TEST_F(EvalKill, ARunRemovesTheTemporaryFilesOfKilledWritesOnly) {
  const fs::path out = path("eval");
  fs::create_directories(out / "plots");
  // No process has this id (pid_max is at most 2^22): these writers were killed.
  const fs::path dead_csv = out / ".cameras.csv.partial-999999999-0";
  const fs::path dead_plot = out / "plots" / ".roofline_render.png.partial-999999999";
  // This test's own process is alive: its temporary may still be renamed into place.
  const fs::path live = out / "plots" / (".notes.txt.partial-" + std::to_string(::getpid()));
  for (const fs::path& p : {dead_csv, dead_plot, live}) std::ofstream(p) << "half a file";
  const testing::CommandResult r = testing::run_tuneray(
      {"eval", "--synthetic-costs", "--scenes", "cornell", "--cameras", "2", "--iterations", "2",
       "--repetitions", "1", "--objective", "render", "--out", out.string(), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(fs::exists(dead_csv));
  EXPECT_FALSE(fs::exists(dead_plot));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(out / "cameras.csv"));
}

}  // namespace
}  // namespace tuneray
