#include "render/frame_budget.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "render/adaptive_sampling.h"

namespace tuneray {

FrameBudgetRenderer::FrameBudgetRenderer(TileRenderer& renderer, double frame_ms,
                                         const ReuseSwitch& reuse)
    : renderer_(renderer),
      frame_ms_(frame_ms),
      reuse_auto_(renderer.settings().quality.path_reuse_auto &&
                  renderer.integrator().reuse_pool_pixels() > 0),
      reuse_switch_(reuse) {
  if (!reuse_auto_) return;
  renderer_.set_path_reuse(reuse_switch_.next_on(0));
  const RenderSettings& s = renderer.settings();
  if (s.quality.adaptive)
    reuse_pixels_.resize(static_cast<size_t>(s.width) * static_cast<size_t>(s.height));
}

FrameBudgetRenderer::~FrameBudgetRenderer() {
  if (reuse_auto_) renderer_.set_reuse_pixels(nullptr);
}

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
  const bool reuse = renderer_.reuse_pool() > 0;
  const PassCost& adaptive = cost(true, reuse);
  return adaptive_ready() && adaptive.ms_per_spp > 0 ? adaptive.ms_per_spp
                                                     : cost(false, reuse).ms_per_spp;
}

double FrameBudgetRenderer::pass_cost_ratio(bool adaptive) const {
  for (bool phase : {adaptive, !adaptive}) {
    const double off = cost(phase, false).ms_per_spp, on = cost(phase, true).ms_per_spp;
    if (off > 0 && on > 0) return on / off;
  }
  return 0;
}

double FrameBudgetRenderer::reuse_cost_ratio(bool adaptive) const {
  return std::max(pass_cost_ratio(adaptive), reuse_switch_.moments().cost_ratio());
}

double FrameBudgetRenderer::plan_pass(bool adaptive, bool reuse, double left_ms) const {
  // A pass costs a fixed overhead plus its samples; folding the overhead into the cost per
  // sample would make small passes look expensive and plan ever smaller ones.
  const PassCost& known = cost(adaptive, reuse);
  if (known.ms_per_spp > 0) return (left_ms - known.overhead_ms) / known.ms_per_spp;
  // A pass without reuse costs at most what one with it does.
  if (!reuse && cost(adaptive, true).ms_per_spp > 0) return plan_pass(adaptive, true, left_ms);
  if (reuse && cost(adaptive, false).ms_per_spp > 0) {
    // Guessed from the same phase without reuse, as a small pass.
    const double ratio = reuse_cost_ratio(adaptive);
    const double without = plan_pass(adaptive, false, left_ms);
    return std::min(kReuseProbePass, without / (ratio > 0 ? ratio : kReuseCostGuess));
  }
  if (adaptive && cost(false, reuse).ms_per_spp > 0)
    return std::min(kAdaptiveProbePass, left_ms / cost(false, reuse).ms_per_spp);
  return kFirstPass;
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
  // Set each frame: the caller may have replaced the renderer (ProgressiveView::set_accel).
  const bool per_pixel = reuse_auto_ && s.quality.adaptive;
  if (per_pixel) renderer_.set_reuse_pixels(&reuse_pixels_);
  for (;;) {
    const bool adaptive = adaptive_ready();
    const double film_spp = static_cast<double>(film_samples_) / pixels;
    if (reuse_auto_) renderer_.set_path_reuse(reuse_switch_.next_on(film_spp));
    const bool reuse = renderer_.reuse_pool() > 0;
    double fit = plan_pass(adaptive, reuse, render_ms - elapsed());
    if (reuse_auto_ && reuse && reuse_switch_.probing()) fit = std::min(fit, kReuseProbePass);
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
    cost(adaptive, reuse)
        .update(pass.render_ms * pixels / samples, std::max(0.0, pass_ms - pass.render_ms));
    film_samples_ += pass.samples;
    if (reuse_auto_ && reuse)
      reuse_switch_.after_reuse_pass(pass.reuse, static_cast<double>(film_samples_) / pixels,
                                     pass_cost_ratio(adaptive),
                                     per_pixel ? &reuse_pixels_ : nullptr);
    frame.stats.accumulate(pass);
    first_pass = false;
  }
  frame.ms = elapsed();
  frame.spp = static_cast<double>(frame.stats.samples) / pixels;
  return frame;
}

}  // namespace tuneray
