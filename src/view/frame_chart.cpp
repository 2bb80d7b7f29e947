#include "view/frame_chart.h"

#include <algorithm>

namespace tuneray {

void FrameChart::add(double ms, FrameKind kind) {
  if (capacity_ == 0) return;
  if (ms_.size() == capacity_) {
    ms_.pop_front();
    kinds_.pop_front();
  }
  ms_.push_back(ms);
  kinds_.push_back(kind);
}

double FrameChart::scale_ms(double budget_ms) const {
  double top = budget_ms;
  for (double ms : ms_) top = std::max(top, ms);
  return top > 0 ? 1.2 * top : 1.0;
}

std::vector<ChartPoint> FrameChart::points(double budget_ms) const {
  std::vector<ChartPoint> out;
  if (ms_.empty()) return out;
  const double scale = scale_ms(budget_ms);
  const double step = capacity_ > 1 ? 1.0 / static_cast<double>(capacity_ - 1) : 0.0;
  const size_t n = ms_.size();
  for (size_t i = 0; i < n; ++i) {
    double x = 1.0 - static_cast<double>(n - 1 - i) * step;
    out.push_back(
        {static_cast<float>(x), static_cast<float>(std::max(0.0, ms_[i]) / scale), kinds_[i]});
  }
  return out;
}

float FrameChart::budget_y(double budget_ms) const {
  return static_cast<float>(budget_ms / scale_ms(budget_ms));
}

}  // namespace tuneray
