// A write that is interrupted (a kill, a full disk, a failing writer) never leaves a truncated
// file or destroys the previous one: files are written aside and renamed (image/atomic_file.h).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include "command_test.h"
#include "run_command.h"

namespace tuneray {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using testing::run_tuneray;

class InterruptedWrites : public testing::CommandTest {};

std::string read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

bool partial_file_exists(const fs::path& dir) {
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().filename().string().find(".partial-") != std::string::npos) return true;
  return false;
}

TEST_F(InterruptedWrites, KilledWhileWritingALargeExrKeepsTheOldFile) {
  const std::string exr = path("image.exr");
  CommandResult first =
      run_tuneray({"render", "cornell", "--spp", "1", "--size", "16x16", "--out", exr, "--quiet"});
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const std::string before = read_all(exr);
  ASSERT_FALSE(before.empty());

  // A 2048 x 2048 direct-light render writes a ~50 MB EXR: kill it as soon as the write begins.
  std::string binary = testing::tuneray_binary();
  pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    execl(binary.c_str(), binary.c_str(), "render", "cornell", "--spp", "1", "--max-bounces", "0",
          "--size", "2048x2048", "--out", exr.c_str(), "--quiet", static_cast<char*>(nullptr));
    _exit(127);
  }
  const fs::path dir = fs::path(exr).parent_path();
  bool seen = false;
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (std::chrono::steady_clock::now() < deadline) {
    if (partial_file_exists(dir)) {
      seen = true;
      kill(pid, SIGKILL);
      break;
    }
    if (waitpid(pid, &status, WNOHANG) == pid) break;  // finished before we saw the write
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  if (seen) waitpid(pid, &status, 0);
  ASSERT_TRUE(seen) << "the render ended before its write was seen";
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(read_all(exr), before) << "the previous image was damaged";
}

TEST_F(InterruptedWrites, AFailedWriteKeepsTheOldReportAndLeavesNoPartialFile) {
  // The report's folder is a file: creating it fails before anything is replaced.
  const std::string report = path("report.json");
  { std::ofstream(report) << "{\"old\": true}\n"; }
  write("blocker", "not a folder");
  CommandResult r = run_tuneray({"render", "cornell", "--spp", "1", "--size", "8x8", "--out",
                                 path("blocker") + "/x.exr", "--report", report, "--quiet"});
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_all(report), "{\"old\": true}\n");
  EXPECT_FALSE(partial_file_exists(fs::path(report).parent_path()));
}

}  // namespace
}  // namespace tuneray
