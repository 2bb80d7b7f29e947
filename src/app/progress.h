// A one-line progress bar on stderr, drawn only when stderr is a terminal and the work takes
// longer than a second. Safe to advance from many threads.
#pragma once

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>

namespace tuneray {

class ProgressBar {
 public:
  ProgressBar(std::string label, uint64_t total, bool enabled);
  ~ProgressBar();
  void advance(uint64_t n = 1);
  void set_suffix(const std::string& suffix);  // e.g. "12.3 Mrays/s"
  void finish();

 private:
  void draw(uint64_t done);
  std::string label_, suffix_;
  uint64_t total_;
  bool enabled_;
  bool drawn_ = false;
  std::atomic<uint64_t> done_{0};
  std::mutex mutex_;
  int last_permille_ = -1;
  std::chrono::steady_clock::time_point start_;
};

bool stderr_is_terminal();

}  // namespace tuneray
