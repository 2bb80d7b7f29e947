// A fresh directory per test for hand-written scene files, removed afterwards.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "scene/load.h"

namespace tuneray::testing {

class SceneFiles {
 public:
  SceneFiles() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("tuneray_scene_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
             std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~SceneFiles() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  SceneFiles(const SceneFiles&) = delete;
  SceneFiles& operator=(const SceneFiles&) = delete;

  std::string path(const std::string& name) const { return (path_ / name).string(); }
  std::string dir() const { return path_.string(); }

  std::string write(const std::string& name, const std::string& text) const {
    const std::string p = path(name);
    std::filesystem::create_directories(std::filesystem::path(p).parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }

 private:
  std::filesystem::path path_;
};

// The message of the SceneError that loading `spec` throws ("" if it loads).
inline std::string load_error(const std::string& spec, const LoadOptions& options = {}) {
  try {
    load_scene(spec, options);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace tuneray::testing
