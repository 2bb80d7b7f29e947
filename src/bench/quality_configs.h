// The rows of the quality ablation: what each configuration switches on.
#pragma once

#include <string>

#include "bench/quality_bench.h"
#include "render/render_settings.h"

namespace tuneray {

// What a row switches on: the render options plus the load-time one-texel folding.
struct QualitySwitches {
  QualityOptions quality;
  bool one_texel = false;
};

// `base` with configuration `name` applied (one of quality_configurations()).
QualitySwitches quality_switches(const std::string& name, const QualityOptions& base,
                                 const QualityBenchOptions& options);

}  // namespace tuneray
