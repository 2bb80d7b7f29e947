// The equal-time quality switches as `render` options (docs/quality.md).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "render/render_settings.h"

namespace tuneray {

struct QualityCli {
  QualityOptions options;
  std::string sky_texels = "rgba";
  std::string sampler = "pcg";
  bool one_texel = true;  // collapse one-texel textures at load time
};

void add_quality_options(CLI::App* cmd, QualityCli& q);
// Validates and returns the options (throws std::invalid_argument on a bad value).
QualityOptions resolve_quality(const QualityCli& q);

}  // namespace tuneray
