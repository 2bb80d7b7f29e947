// `mpirun -n N tuneray eval` on this machine (--oversubscribe: 2 cores may host 3 ranks), with
// synthetic costs so that the numbers do not depend on which rank measured what: a 2-rank run
// writes the same report as the 1-rank run, byte for byte (hence the same set of jobs), and a
// run whose worker rank is SIGKILLed mid-run resumes with another number of ranks, redoing no
// search rank 0 had reported stored, and ends with that same report. Skipped, saying why, when
// mpirun is absent or tuneray was built without MPI.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include "command_test.h"
#include "report_files.h"
#include "run_command.h"

namespace tuneray {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const std::map<std::string, std::optional<std::string>> kMpiEnvironment = {
    // CI runs as root, which mpirun refuses without these.
    {"OMPI_ALLOW_RUN_AS_ROOT", "1"},
    {"OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1"},
    // In the sanitizer build: OpenMPI's memory patcher rewrites the allocator entry points ASan
    // intercepts and crashes MPI_Init (open-mpi/ompi#12819, #13069); it only speeds up RDMA
    // networks, which a test on one machine does not use.
    {"OMPI_MCA_memory", "^patcher"},
    // In the sanitizer build: OpenMPI leaks thousands of blocks at exit from components whose
    // stacks LeakSanitizer cannot unwind ("<unknown module>"), so no suppression can name them.
    // Leak checking stays on for our coordinator and workers in tuning_tests (EvalRanks), which
    // run the same code without MPI.
    {"ASAN_OPTIONS", "detect_leaks=0"},
};

// Marks this test process's ranks, so the kill below never hits the ranks of another MPI test
// that ctest runs at the same time.
std::string rank_mark() {
  return "TUNERAY_RANK_TEST=" + std::to_string(getpid());
}

std::vector<std::string> mpirun_args(int ranks, const std::vector<std::string>& eval_args) {
  // --bind-to none: tuneray pins its ranks itself (rank_cores.h).
  std::vector<std::string> argv = {
      TUNERAY_MPIEXEC,       "--oversubscribe",        "--bind-to", "none", "-x", rank_mark(), "-n",
      std::to_string(ranks), testing::tuneray_binary()};
  argv.insert(argv.end(), eval_args.begin(), eval_args.end());
  return argv;
}

// (scene objective camera) of every stored job with search frames, from rank 0's progress lines.
// Parsed by hand: std::regex trips GCC 12's -Wmaybe-uninitialized in the sanitizer build.
std::set<std::string> stored_searches(const std::string& log) {
  std::set<std::string> searches;
  std::istringstream lines(log);
  std::string line;
  const std::string marker = "stored; rank ", frames = " search frames";
  while (std::getline(lines, line)) {
    const size_t start = line.find(marker);
    if (start == std::string::npos) continue;
    const size_t job = line.find(": ", start);
    const size_t comma = line.find(", ", job == std::string::npos ? start : job);
    const size_t end = line.find(frames, comma == std::string::npos ? start : comma);
    if (job == std::string::npos || comma == std::string::npos || end == std::string::npos)
      continue;
    // "SCENE OBJECTIVE camera N", then the frame count.
    const std::string name = line.substr(job + 2, comma - job - 2);
    if (std::stoi(line.substr(comma + 2, end - comma - 2)) > 0) searches.insert(name);
  }
  return searches;
}

class EvalMpi : public testing::CommandTest {
 protected:
  void SetUp() override {
    if (std::string(TUNERAY_MPIEXEC).empty())
      GTEST_SKIP() << "mpirun not found at configure time (scripts/install-deps installs "
                      "openmpi-bin)";
    if (!TUNERAY_WITH_MPI)
      GTEST_SKIP() << "tuneray built without MPI (libopenmpi-dev absent at configure time)";
  }

  std::vector<std::string> eval_args(const fs::path& out, const std::vector<std::string>& more) {
    std::vector<std::string> args = {"eval",  "--profile", "quick", "--synthetic-costs",
                                     "--out", out.string()};
    args.insert(args.end(), more.begin(), more.end());
    return args;
  }
};

// Runs `eval_args` on one rank (no mpirun) into `out`, and moves its report aside: report.md
// quotes the command and plot scripts name files, so the runs compared must use the same --out.
std::map<std::string, std::string> one_rank_report(const std::vector<std::string>& eval_args,
                                                   const fs::path& out) {
  const testing::ProgramResult single = testing::run_tuneray(eval_args);
  EXPECT_EQ(single.exit_code, 0) << single.output;
  auto files = testing::report_files(out);
  fs::remove_all(out);
  return files;
}

TEST_F(EvalMpi, TwoRanksWriteTheOneRankReport) {
  const fs::path out = path("eval");
  const auto t0 = Clock::now();
  const auto reference = one_rank_report(eval_args(out, {"--quiet"}), out);
  const auto t1 = Clock::now();
  const testing::ProgramResult ranks =
      testing::run_program(mpirun_args(2, eval_args(out, {"--quiet"})), kMpiEnvironment);
  const auto t2 = Clock::now();
  ASSERT_FALSE(ranks.signaled) << ranks.output;
  ASSERT_EQ(ranks.exit_code, 0) << ranks.output;
  EXPECT_NE(ranks.output.find("2 ranks on this node share"), std::string::npos) << ranks.output;
  EXPECT_NE(ranks.output.find("rank 1 on core"), std::string::npos) << ranks.output;
  std::cout << "quick profile, synthetic costs: 1 rank "
            << std::chrono::duration<double>(t1 - t0).count() << " s, 2 ranks (mpirun) "
            << std::chrono::duration<double>(t2 - t1).count() << " s\n";

  // The same jobs: one row per (scene, objective, camera), 2 x 2 x 6 in the quick profile.
  ASSERT_TRUE(reference.count("cameras.csv"));
  std::istringstream rows(reference.at("cameras.csv"));
  size_t lines = 0;
  for (std::string l; std::getline(rows, l);) ++lines;
  EXPECT_EQ(lines, 1u + 2u * 2u * 6u);
  // And the same report, byte for byte.
  EXPECT_EQ(testing::differences(reference, testing::report_files(out)), "");
}

TEST_F(EvalMpi, AFailingStudyEndsEveryRankWithItsError) {
  // Rank 0 fails (the scene does not exist) while rank 1 waits for jobs: both must end.
  const testing::ProgramResult r = testing::run_program(
      mpirun_args(2, eval_args(path("eval"), {"--scenes", "no-such-scene"})), kMpiEnvironment);
  EXPECT_FALSE(r.signaled) << r.output;
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("tuneray: error: no-such-scene"), std::string::npos) << r.output;
}

// Runs mpirun with output to `log`; once rank 0 has reported `stored` jobs, SIGKILLs rank 1.
struct KilledRun {
  bool killed_worker = false;
  int exit_code = -1;
  bool finished_before_kill = false;
};
KilledRun run_and_kill_worker(const std::vector<std::string>& args, const std::string& log,
                              size_t stored) {
  std::vector<std::string> copies = args;
  std::vector<char*> argv;
  for (std::string& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, STDOUT_FILENO);
    dup2(fd, STDERR_FILENO);
    for (const auto& [k, v] : kMpiEnvironment) setenv(k.c_str(), v->c_str(), 1);
    execv(argv[0], argv.data());
    _exit(127);
  }
  KilledRun run;
  int status = 0;
  const auto start = Clock::now();
  for (;;) {
    if (waitpid(pid, &status, WNOHANG) == pid) {
      run.finished_before_kill = !run.killed_worker;
      break;
    }
    if (Clock::now() - start > std::chrono::seconds(120)) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      break;
    }
    if (!run.killed_worker && stored_searches(testing::read_all(log)).size() >= stored) {
      // Rank 1 is the process whose environment says so (and carries our mark).
      for (const auto& entry : fs::directory_iterator("/proc")) {
        const std::string env = testing::read_all(entry.path() / "environ");
        if (env.find(rank_mark() + '\0') != std::string::npos &&
            env.find(std::string("OMPI_COMM_WORLD_RANK=1") + '\0') != std::string::npos) {
          kill(std::stoi(entry.path().filename().string()), SIGKILL);
          run.killed_worker = true;
        }
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

TEST_F(EvalMpi, AKilledRankLosesNothingStoredAndTheRunResumesWithOtherRanks) {
  // More cameras and frames than the profile's, so that the kill lands mid-study; the BVH
  // alone, so that the comparisons of the second round of jobs have predictions to measure.
  const std::vector<std::string> more = {"--objective",  "render", "--cameras",   "24",
                                         "--iterations", "40",     "--tuned-only"};
  const fs::path out = path("eval");
  const auto reference = one_rank_report(eval_args(out, more), out);
  ASSERT_FALSE(reference.empty());

  const std::string log = path("killed.log");
  const KilledRun killed = run_and_kill_worker(mpirun_args(2, eval_args(out, more)), log, 3);
  const std::string killed_log = testing::read_all(log);
  ASSERT_FALSE(killed.finished_before_kill) << "the run ended before rank 1 could be killed\n"
                                            << killed_log;
  ASSERT_TRUE(killed.killed_worker) << killed_log;
  EXPECT_NE(killed.exit_code, 0) << "mpirun must fail when a rank dies\n" << killed_log;
  const std::set<std::string> reported = stored_searches(killed_log);
  ASSERT_GE(reported.size(), 3u);

  // Resumed with 3 ranks (2 measuring).
  const testing::ProgramResult resumed =
      testing::run_program(mpirun_args(3, eval_args(out, more)), kMpiEnvironment);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  const std::set<std::string> searched_again = stored_searches(resumed.output);
  std::cout << "rank 1 killed after rank 0 had stored " << reported.size()
            << " searches; the 3-rank resume stored " << searched_again.size() << " more\n";
  EXPECT_EQ(reported.size() + searched_again.size(), 2u * 24u);  // 2 scenes, 24 cameras
  for (const std::string& search : searched_again)
    EXPECT_FALSE(reported.count(search)) << search << " was stored before the kill, searched again";

  EXPECT_EQ(testing::differences(reference, testing::report_files(out)), "");
}

}  // namespace
}  // namespace tuneray
