#include "tuning/line_log.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <stdexcept>

#include "common/temp_dir.h"

namespace tuneray {
namespace {

std::string read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

TEST(LineLog, ValuesSurviveAReopenAndALaterLineReplacesAnEarlierOne) {
  testing::TempDir dir;
  const std::string path = dir.file("log.tsv");
  {
    LineLog log(path, "run");
    log.add("run\t0", "{\"a\":1}");
    log.add("run\t1", "b c");
    log.add("run\t0", "{\"a\":2}");
    EXPECT_EQ(*log.find("run\t0"), "{\"a\":2}");
  }
  EXPECT_EQ(read_all(path), "run\t0\t{\"a\":1}\nrun\t1\tb c\nrun\t0\t{\"a\":2}\n");
  LineLog again(path, "run");
  EXPECT_EQ(*again.find("run\t0"), "{\"a\":2}");
  EXPECT_EQ(*again.find("run\t1"), "b c");
  EXPECT_FALSE(again.find("run\t2").has_value());
}

TEST(LineLog, OtherRunsAreNotRead) {
  testing::TempDir dir;
  const std::string path = dir.write_bytes("log.tsv", "other\t0\ta\nrun\t0\tb\n");
  LineLog log(path, "run");
  EXPECT_FALSE(log.find("other\t0").has_value());
  EXPECT_EQ(*log.find("run\t0"), "b");
  EXPECT_THROW(log.add("other\t1", "c"), std::invalid_argument);
}

TEST(LineLog, ALineTornByAKillIsNeverRead) {
  testing::TempDir dir;
  // A kill cut "0.123456" after "0.12": read as a value it would be silently wrong.
  const std::string path = dir.write_bytes("log.tsv", "run\t0\t5.000000\nrun\t1\t0.12");
  LineLog log(path, "run");
  EXPECT_EQ(*log.find("run\t0"), "5.000000");
  EXPECT_FALSE(log.find("run\t1").has_value());
  // The next line first closes the torn one with a mark, so it never becomes "0.12".
  log.add("run\t2", "3.000000");
  EXPECT_EQ(read_all(path), "run\t0\t5.000000\nrun\t1\t0.12 (torn by a kill)\nrun\t2\t3.000000\n");
  LineLog again(path, "run");
  EXPECT_EQ(*again.find("run\t1"), "0.12 (torn by a kill)");  // whole, but no longer a number
  EXPECT_EQ(*again.find("run\t2"), "3.000000");
}

TEST(LineLog, RefusesLinesThatWouldNotReadBackAsWritten) {
  testing::TempDir dir;
  LineLog log(dir.file("log.tsv"), "run");
  EXPECT_THROW(log.add("run\t0", "a\tb"), std::invalid_argument);
  EXPECT_THROW(log.add("run\t0", "a\nb"), std::invalid_argument);
  EXPECT_THROW(log.add("run\n0", "a"), std::invalid_argument);
  EXPECT_FALSE(log.find("run\t0").has_value());
}

}  // namespace
}  // namespace tuneray
