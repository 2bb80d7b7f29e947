#include "view/view_status.h"

#include <fmt/core.h>

namespace tuneray {

std::string format_title(const ViewStatus& s) {
  const double fps = s.frame_ms > 0 ? 1000.0 / s.frame_ms : 0.0;
  std::string title = fmt::format(
      "{}{} | {:.1f} ms/frame ({:.1f} fps, render {:.1f} ms) | {:.2f} spp/frame, {:.1f} spp | "
      "{}, {} | {}",
      s.scene, s.playing_path ? " [path]" : "", s.frame_ms, fps, s.render_ms, s.frame_spp,
      s.film_spp, s.adaptive ? "adaptive" : "uniform", s.sampler, s.accel);
  return s.tuning.empty() ? title : title + " | " + s.tuning;
}

std::string format_tuning(const ViewTuneStatus& t) {
  auto ratio = [](double r) { return r > 0 ? fmt::format("{:.2f}x", r) : std::string("-"); };
  return fmt::format("{} {:.3f} ms/spp, {} over default, {} over native | {}", t.mode, t.current_ms,
                     ratio(t.default_ms > 0 ? t.speedup() : 0),
                     ratio(t.native_ms > 0 ? t.vs_native() : 0), t.config);
}

}  // namespace tuneray
