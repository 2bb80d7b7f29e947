#include "render/frame_budget.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "render/adaptive_sampling.h"

namespace tuneray {

bool FrameBudgetRenderer::adaptive_ready() const {
  const QualityOptions& q = renderer_.settings().quality;
  return q.adaptive && uniform_samples_ >= static_cast<uint32_t>(std::max(2, q.adaptive_min_spp));
}

PassStats FrameBudgetRenderer::add_samples(Film& film, double spp) {
  const RenderSettings& s = renderer_.settings();
  const size_t pixels = static_cast<size_t>(s.width) * s.height;
  if (adaptive_ready()) {
    auto samples = static_cast<uint64_t>(std::llround(spp * static_cast<double>(pixels)));
    return renderer_.render_extra(film,
                                  allocate_adaptive_samples(film, std::max<uint64_t>(1, samples)));
  }
  if (spp < 1.0 || partial_cursor_ != 0) return add_partial_pass(film, spp);
  auto whole = static_cast<uint32_t>(std::clamp(std::floor(spp), 1.0, 1e6));
  if (!s.quality.adaptive) {
    PassStats stats = renderer_.render_pass(film, uniform_samples_, whole);
    uniform_samples_ += whole;
    return stats;
  }
  // Uniform warm-up until the variance can be trusted; never past it, so the adaptive passes
  // start as early as they may.
  uint32_t min_spp = static_cast<uint32_t>(std::max(2, s.quality.adaptive_min_spp));
  whole = std::min(whole, min_spp - uniform_samples_);
  uniform_samples_ += whole;
  return renderer_.render_extra(film, std::vector<uint32_t>(pixels, whole));
}

PassStats FrameBudgetRenderer::add_partial_pass(Film& film, double spp) {
  const RenderSettings& s = renderer_.settings();
  const size_t pixels = static_cast<size_t>(s.width) * s.height;
  const auto wanted = static_cast<size_t>(std::llround(std::min(spp, 1.0) * pixels));
  const size_t count = std::clamp<size_t>(wanted, 1, pixels - partial_cursor_);
  std::vector<uint32_t> extra(pixels, 0);
  std::fill_n(extra.begin() + static_cast<std::ptrdiff_t>(partial_cursor_), count, 1u);
  // render_extra continues each pixel's sample indices from the film, so a round of partial
  // passes gives every pixel the same sample a whole pass would have.
  PassStats stats = renderer_.render_extra(film, extra);
  partial_cursor_ += count;
  if (partial_cursor_ == pixels) {
    partial_cursor_ = 0;
    ++uniform_samples_;
  }
  return stats;
}

void FrameBudgetRenderer::PassCost::update(double per_spp, double overhead) {
  const bool first = ms_per_spp <= 0;
  ms_per_spp = first ? per_spp : 0.5 * ms_per_spp + 0.5 * per_spp;
  overhead_ms = first ? overhead : 0.5 * overhead_ms + 0.5 * overhead;
}

double FrameBudgetRenderer::ms_per_spp() const {
  return adaptive_ready() && adaptive_cost_.ms_per_spp > 0 ? adaptive_cost_.ms_per_spp
                                                           : uniform_cost_.ms_per_spp;
}

FrameResult FrameBudgetRenderer::render_frame(Film& film, double reserved_ms) {
  const double render_ms = frame_ms_ - std::max(0.0, reserved_ms);
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
    const bool adaptive = adaptive_ready();
    PassCost& cost = adaptive ? adaptive_cost_ : uniform_cost_;
    // A pass costs a fixed overhead plus its samples; folding the overhead into the cost per
    // sample would make small passes look expensive and plan ever smaller ones.
    double fit;
    if (cost.ms_per_spp > 0) {
      fit = (render_ms - elapsed() - cost.overhead_ms) / cost.ms_per_spp;
    } else if (adaptive && uniform_cost_.ms_per_spp > 0) {
      double uniform_fit = (render_ms - elapsed()) / uniform_cost_.ms_per_spp;
      fit = std::min(kAdaptiveProbePass, uniform_fit);
    } else {
      fit = kFirstPass;
    }
    // Every frame gets at least one pass, of at least the smallest size.
    if (fit < kSmallestPass) {
      if (!first_pass) break;
      fit = kSmallestPass;
    }
    auto t0 = std::chrono::steady_clock::now();
    PassStats pass = add_samples(film, std::min(fit, 1e6));
    double pass_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    double samples = std::max(1.0, static_cast<double>(pass.samples));
    cost.update(pass.render_ms * pixels / samples, std::max(0.0, pass_ms - pass.render_ms));
    frame.stats.accumulate(pass);
    first_pass = false;
  }
  frame.ms = elapsed();
  frame.spp = static_cast<double>(frame.stats.samples) / pixels;
  return frame;
}

}  // namespace tuneray
