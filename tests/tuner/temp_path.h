// Unique temporary database paths, removed (with their WAL files) at the end of the test.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

namespace tuneray::tuner::testing {

class TempPath {
 public:
  explicit TempPath(const std::string& name)
      : path_((std::filesystem::temp_directory_path() /
               ("tuner_test_" + std::to_string(::getpid()) + "_" + name))
                  .string()) {
    remove_all();
  }
  ~TempPath() { remove_all(); }
  const std::string& str() const { return path_; }

 private:
  void remove_all() const {
    for (const char* suffix : {"", "-wal", "-shm"}) std::remove((path_ + suffix).c_str());
  }
  std::string path_;
};

}  // namespace tuneray::tuner::testing
