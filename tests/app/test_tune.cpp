// `tuneray tune`: the loop runs end to end, and a second run on the same database starts with
// trained predictors (nothing is searched again when epsilon = 0).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "run_command.h"

namespace tuneray {
namespace {

namespace fs = std::filesystem;

TEST(Tune, SecondRunOnTheSameDatabaseUsesWhatWasLearnt) {
  fs::path db = fs::temp_directory_path() / ("tuneray-tune-" + std::to_string(::getpid()) + ".db");
  fs::remove(db);
  std::vector<std::string> common = {"tune",         "cornell",   "--cameras", "3",
                                     "--iterations", "6",         "--size",    "32x18",
                                     "--db",         db.string(), "--quiet"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = common;
    args.insert(args.end(), extra.begin(), extra.end());
    return testing::run_tuneray(args);
  };
  testing::CommandResult first = with({"--epsilon", "1"});
  ASSERT_FALSE(first.signaled) << first.output;
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find("3 of 3 cameras searched"), std::string::npos) << first.output;

  testing::CommandResult second = with({"--epsilon", "0"});
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(second.output.find("0 of 3 cameras searched"), std::string::npos) << second.output;

  // A corrupted database is refused with its name, and left as it was.
  fs::remove(db.string() + "-wal");
  fs::remove(db.string() + "-shm");
  { std::ofstream(db, std::ios::trunc) << "this is not a tuning database"; }
  testing::CommandResult corrupt = with({});
  EXPECT_FALSE(corrupt.signaled);
  EXPECT_NE(corrupt.exit_code, 0);
  EXPECT_NE(corrupt.output.find(db.filename().string()), std::string::npos) << corrupt.output;
  EXPECT_EQ(fs::file_size(db), std::string("this is not a tuning database").size());
  fs::remove(db);
}

}  // namespace
}  // namespace tuneray
