// `tuneray tune --work-sizes` end to end: the option is accepted, the run succeeds on a built-in
// scene, and its summary names the work-size parameters beside the BVH ones.
#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>

#include "run_command.h"

namespace tuneray {
namespace {

namespace fs = std::filesystem;

TEST(TuneCli, WorkSizesJoinTheSearch) {
  fs::path db =
      fs::temp_directory_path() / ("tuneray-tune-cli-" + std::to_string(::getpid()) + ".db");
  fs::remove(db);
  testing::CommandResult r = testing::run_tuneray(
      {"tune", "cornell", "--cameras", "1", "--iterations", "4", "--size", "32x18", "--epsilon",
       "1", "--db", db.string(), "--quiet", "--work-sizes"});
  ASSERT_FALSE(r.signaled) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("scheduler, tile_size, batch_size"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 of 1 cameras searched"), std::string::npos) << r.output;
  // The chosen configuration: the BVH parameters, then the scheduler and its active size.
  EXPECT_NE(r.output.find("robust="), std::string::npos) << r.output;
  const bool tile = r.output.find(",scheduler=tile,tile_size=") != std::string::npos;
  const bool wave = r.output.find(",scheduler=wavefront,batch_size=") != std::string::npos;
  EXPECT_TRUE(tile || wave) << r.output;

  // Without the option the summary stays BVH only, on the same database.
  testing::CommandResult plain =
      testing::run_tuneray({"tune", "cornell", "--cameras", "1", "--iterations", "2", "--size",
                            "32x18", "--db", db.string(), "--quiet"});
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_EQ(plain.output.find("scheduler"), std::string::npos) << plain.output;
  fs::remove(db);
  fs::remove(db.string() + "-wal");
  fs::remove(db.string() + "-shm");
}

}  // namespace
}  // namespace tuneray
