#include "app/progress.h"

#include <unistd.h>

#include <cstdio>

namespace tuneray {

bool stderr_is_terminal() {
  return isatty(STDERR_FILENO) != 0;
}

ProgressBar::ProgressBar(std::string label, uint64_t total, bool enabled)
    : label_(std::move(label)),
      total_(total > 0 ? total : 1),
      enabled_(enabled),
      start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() {
  finish();
}

void ProgressBar::set_suffix(const std::string& suffix) {
  std::lock_guard lock(mutex_);
  suffix_ = suffix;
}

void ProgressBar::advance(uint64_t n) {
  uint64_t done = done_.fetch_add(n) + n;
  if (!enabled_) return;
  std::unique_lock lock(mutex_, std::try_to_lock);
  if (lock.owns_lock()) draw(done);
}

void ProgressBar::draw(uint64_t done) {
  double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (elapsed < 1.0) return;  // short work stays silent
  int permille = static_cast<int>(1000 * std::min<uint64_t>(done, total_) / total_);
  if (permille == last_permille_) return;
  last_permille_ = permille;
  constexpr int kWidth = 30;
  int filled = permille * kWidth / 1000;
  double eta = permille > 0 ? elapsed * (1000 - permille) / permille : 0;
  std::fprintf(stderr, "\r%s [%.*s%*s] %5.1f%% %6.1fs left %s", label_.c_str(), filled,
               "##############################", kWidth - filled, "", permille / 10.0, eta,
               suffix_.c_str());
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::finish() {
  std::lock_guard lock(mutex_);
  if (drawn_) {
    std::fprintf(stderr, "\n");
    drawn_ = false;
  }
}

}  // namespace tuneray
