#include "render/frame_budget.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "render/adaptive_sampling.h"

namespace tuneray {

PassStats FrameBudgetRenderer::add_samples(Film& film, uint32_t spp) {
  const RenderSettings& s = renderer_.settings();
  if (!s.quality.adaptive) {
    PassStats stats = renderer_.render_pass(film, next_sample_, spp);
    next_sample_ += spp;
    return stats;
  }
  const size_t pixels = static_cast<size_t>(s.width) * s.height;
  uint32_t min_spp = static_cast<uint32_t>(std::max(2, s.quality.adaptive_min_spp));
  if (min_samples_ < min_spp) {  // uniform warm-up until the variance can be trusted
    min_samples_ += spp;
    return renderer_.render_extra(film, std::vector<uint32_t>(pixels, spp));
  }
  return renderer_.render_extra(film, allocate_adaptive_samples(film, uint64_t{spp} * pixels));
}

FrameResult FrameBudgetRenderer::render_frame(Film& film) {
  const RenderSettings& s = renderer_.settings();
  const double pixels = static_cast<double>(s.width) * s.height;
  auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
  };
  FrameResult frame;
  bool first_pass = true;
  for (;;) {
    double left = frame_ms_ - elapsed();
    uint32_t spp = 1;
    if (ms_per_spp_ > 0) {
      double fit = std::floor(left / ms_per_spp_);
      if (fit < 1) {
        if (!first_pass) break;
        fit = 1;  // every frame gets at least one sample per pixel
      }
      spp = static_cast<uint32_t>(std::min(fit, 1e6));
    }
    auto t0 = std::chrono::steady_clock::now();
    PassStats pass = add_samples(film, spp);
    double pass_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    double per_spp = pass_ms * pixels / std::max<double>(1.0, static_cast<double>(pass.samples));
    ms_per_spp_ = ms_per_spp_ > 0 ? 0.5 * ms_per_spp_ + 0.5 * per_spp : per_spp;
    frame.stats.accumulate(pass);
    first_pass = false;
  }
  frame.ms = elapsed();
  frame.spp = static_cast<double>(frame.stats.samples) / pixels;
  return frame;
}

}  // namespace tuneray
