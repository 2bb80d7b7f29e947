#include "accel/build_bench.h"

#include <algorithm>

namespace tuneray {

namespace {
double median_of(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
}  // namespace

NativeOptions native_options_for(const BvhConfig& config) {
  NativeOptions options;
  switch (config.quality) {
    case BvhQuality::kLow:
      options.quality = RTC_BUILD_QUALITY_LOW;
      break;
    case BvhQuality::kHigh:
      options.quality = RTC_BUILD_QUALITY_HIGH;
      break;
    default:
      options.quality = RTC_BUILD_QUALITY_MEDIUM;
      break;
  }
  return options;
}

BuildComparison compare_build_times(const GeometryView& geometry, TunedBvhAccel& tuned,
                                    EmbreeNativeAccel& native, int repeats) {
  native.set_options(native_options_for(tuned.config()));
  BuildComparison out;
  tuned.build(geometry);
  native.build(geometry);
  for (int r = 0; r < std::max(1, repeats); ++r) {
    out.tuned = tuned.build(geometry);
    out.tuned_ms.push_back(out.tuned.build_ms);
    out.native_ms.push_back(native.build(geometry).build_ms);
  }
  out.tuned_median_ms = median_of(out.tuned_ms);
  out.native_median_ms = median_of(out.native_ms);
  out.ratio = out.native_median_ms > 0 ? out.tuned_median_ms / out.native_median_ms : 0;
  out.tuned.build_ms = out.tuned_median_ms;
  return out;
}

}  // namespace tuneray
