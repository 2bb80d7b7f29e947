// `tuneray tune --work-sizes` end to end: the option is accepted, the run succeeds on a built-in
// scene, and its summary names the work-size parameters beside the BVH ones.
#include <gtest/gtest.h>

#include "run_command.h"
#include "tuner/temp_path.h"

namespace tuneray {
namespace {

TEST(TuneCli, WorkSizesJoinTheSearch) {
  const tuner::testing::TempPath db("tune-cli-work-sizes.db");
  testing::CommandResult r = testing::run_tuneray(
      {"tune", "cornell", "--cameras", "1", "--iterations", "4", "--size", "32x18", "--epsilon",
       "1", "--db", db.str(), "--quiet", "--work-sizes"});
  ASSERT_FALSE(r.signaled) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("scheduler, tile_size, batch_size"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 of 1 cameras searched"), std::string::npos) << r.output;
  // The chosen configuration: the backend (and BVH parameters under tuned), then the scheduler
  // and its active size.
  EXPECT_NE(r.output.find("  backend="), std::string::npos) << r.output;
  const bool tile = r.output.find(",scheduler=tile,tile_size=") != std::string::npos;
  const bool wave = r.output.find(",scheduler=wavefront,batch_size=") != std::string::npos;
  EXPECT_TRUE(tile || wave) << r.output;

  // Without the option the configurations name no work size, on the same database.
  testing::CommandResult plain =
      testing::run_tuneray({"tune", "cornell", "--cameras", "1", "--iterations", "2", "--size",
                            "32x18", "--db", db.str(), "--quiet"});
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_EQ(plain.output.find(",scheduler="), std::string::npos) << plain.output;
  EXPECT_NE(plain.output.find("  backend="), std::string::npos) << plain.output;
}

}  // namespace
}  // namespace tuneray
