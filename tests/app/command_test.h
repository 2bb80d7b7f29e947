// A fixture for tests that run the tuneray binary: a fresh directory per test, removed
// afterwards, so tests never see each other's files.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "common/temp_dir.h"

namespace tuneray::testing {

class CommandTest : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return dir_.file(name); }
  std::string write(const std::string& name, const std::string& content) const {
    return dir_.write_bytes(name, content);
  }

 private:
  TempDir dir_;
};

}  // namespace tuneray::testing
