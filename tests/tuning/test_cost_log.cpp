#include "tuning/cost_log.h"

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

TEST(CostLog, ValuesSurviveAReopenExactly) {
  testing::TempDir dir;
  const std::string path = dir.file("costs.tsv");
  {
    CostLog log(path, "run");
    // The value returned is the one a reopened log reads, not the one given.
    EXPECT_EQ(log.add("run\t0\ta", 12.3456789), 12.345679);
    EXPECT_EQ(log.add("run\t1\tb", 0.5), 0.5);
    EXPECT_EQ(*log.find("run\t0\ta"), 12.345679);  // as written: 6 decimals
  }
  CostLog again(path, "run");
  EXPECT_EQ(*again.find("run\t0\ta"), 12.345679);
  EXPECT_EQ(*again.find("run\t1\tb"), 0.5);
  EXPECT_FALSE(again.find("run\t2\tc").has_value());
}

TEST(CostLog, OtherRunsAreNotRead) {
  testing::TempDir dir;
  const std::string path =
      dir.write_bytes("costs.tsv", "other\t0\ta\t1.000000\nrun\t0\ta\t2.000000\n");
  CostLog log(path, "run");
  EXPECT_EQ(log.entries().size(), 1u);
  EXPECT_EQ(*log.find("run\t0\ta"), 2.0);
}

TEST(CostLog, ALineTornByAKillIsNeverReadAsAValue) {
  testing::TempDir dir;
  // A kill cut "0.123456" after "0.12": read as a number it would be silently wrong.
  const std::string path = dir.write_bytes("costs.tsv", "run\t0\ta\t5.000000\nrun\t1\tb\t0.12");
  CostLog log(path, "run");
  EXPECT_EQ(*log.find("run\t0\ta"), 5.0);
  EXPECT_FALSE(log.find("run\t1\tb").has_value());
  // Another measurement first: the torn line is closed with a mark, never becoming "0.12".
  log.add("run\t2\tc", 3.0);
  EXPECT_EQ(read_all(path),
            "run\t0\ta\t5.000000\nrun\t1\tb\t0.12 (torn by a kill)\nrun\t2\tc\t3.000000\n");
  CostLog again(path, "run");
  EXPECT_FALSE(again.find("run\t1\tb").has_value());
  EXPECT_EQ(*again.find("run\t2\tc"), 3.0);
}

TEST(CostLog, MangledLinesAreSkipped) {
  testing::TempDir dir;
  const std::string path =
      dir.write_bytes("costs.tsv", "run\t0\ta\t1.5x\nrun\t0\tb\tnotanumber\nrun\t0\tc\t2.250000\n");
  CostLog log(path, "run");
  EXPECT_EQ(log.entries().size(), 1u);
  EXPECT_EQ(*log.find("run\t0\tc"), 2.25);
}

}  // namespace
}  // namespace tuneray
