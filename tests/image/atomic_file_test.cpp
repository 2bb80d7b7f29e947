#include "image/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "common/temp_dir.h"

namespace tuneray {
namespace {

namespace fs = std::filesystem;

std::string read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

size_t files_in(const std::string& dir) {
  return static_cast<size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(ReplaceFile, ReplacesTheContentOnSuccess) {
  testing::TempDir dir;
  std::string path = dir.write_bytes("a.txt", "old");
  replace_file(path, [](const std::string& temporary) { std::ofstream(temporary) << "new"; });
  EXPECT_EQ(read_all(path), "new");
  EXPECT_EQ(files_in(dir.file("")), 1u);
}

TEST(ReplaceFile, AFailingWriterLeavesTheOldFileAndNoTemporary) {
  testing::TempDir dir;
  std::string path = dir.write_bytes("a.txt", "old");
  EXPECT_THROW(replace_file(path,
                            [](const std::string& temporary) {
                              std::ofstream(temporary) << "half";
                              throw std::runtime_error("disk full");
                            }),
               std::runtime_error);
  EXPECT_EQ(read_all(path), "old");
  EXPECT_EQ(files_in(dir.file("")), 1u);
}

TEST(ReplacingFile, UncommittedContentNeverReachesTheFile) {
  testing::TempDir dir;
  std::string path = dir.write_bytes("r.json", "old");
  {
    ReplacingFile f(path);
    f << "new";
  }
  EXPECT_EQ(read_all(path), "old");
  EXPECT_EQ(files_in(dir.file("")), 1u);
  {
    ReplacingFile f(path);
    f << "new " << 42;
    f.commit();
  }
  EXPECT_EQ(read_all(path), "new 42");
  EXPECT_EQ(files_in(dir.file("")), 1u);
}

TEST(ReplacingFile, AMissingFolderIsNamed) {
  testing::TempDir dir;
  std::string path = dir.file("missing/r.json");
  try {
    ReplacingFile f(path);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tuneray
