// The strip chart of frame times: the last N frames' milliseconds as a polyline, newest on the
// right, against a scale that holds the budget line and the slowest frame shown. Kept apart
// from drawing so the geometry can be checked without a window.
#pragma once

#include <cstddef>
#include <deque>
#include <vector>

namespace tuneray {

// What a frame did, for its colour: with --tune the chart is the tuning trace, searched
// frames apart from exploited ones and from the yardsticks.
enum class FrameKind { kPlain, kSearch, kExploit, kYardstick };

struct ChartPoint {
  float x, y;  // in [0, 1]: x 0 = oldest slot, 1 = newest; y 0 = 0 ms, 1 = the scale's top
  FrameKind kind;
};

class FrameChart {
 public:
  explicit FrameChart(size_t capacity) : capacity_(capacity) {}

  void add(double ms, FrameKind kind = FrameKind::kPlain);
  void clear() {
    ms_.clear();
    kinds_.clear();
  }
  size_t size() const { return ms_.size(); }

  // The chart's top in ms: the larger of the slowest frame shown and `budget_ms`, with 20%
  // headroom so neither touches the edge.
  double scale_ms(double budget_ms) const;
  // One point per frame, right-aligned: the newest frame is at x = 1 and older ones step left
  // by 1 / (capacity - 1), so the chart scrolls as frames arrive.
  std::vector<ChartPoint> points(double budget_ms) const;
  // Height of the budget line on the same scale.
  float budget_y(double budget_ms) const;

 private:
  size_t capacity_;
  std::deque<double> ms_;
  std::deque<FrameKind> kinds_;
};

}  // namespace tuneray
