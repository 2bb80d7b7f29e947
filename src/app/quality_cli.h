// The equal-time quality switches as `render` options (docs/quality.md). Every default comes
// from QualityOptions{}, so the command line and the library agree on what the measured
// defaults are.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "render/render_settings.h"

namespace tuneray {

struct QualityCli {
  QualityOptions options;
  std::string scheduler = options.wavefront ? "wavefront" : "tile";
  std::string sky_texels = options.sky_rgba ? "rgba" : "rgb";
  std::string sampler = options.sampler == SamplerKind::kBlueNoise ? "bluenoise" : "pcg";
  std::string materials = options.branchless_materials ? "branchless" : "by-type";
  std::string sky_sampling = options.bsdf_sky ? "bsdf" : "uniform";
  bool adaptive_on = false, adaptive_off = false;  // --adaptive / --no-adaptive given
  // --path-reuse: off, auto or a pool size (QualityOptions::path_reuse and path_reuse_auto).
  std::string path_reuse = options.path_reuse < 2    ? "off"
                           : options.path_reuse_auto ? "auto"
                                                     : std::to_string(options.path_reuse);
  bool one_texel = true;  // collapse one-texel textures at load time
};

void add_quality_options(CLI::App* cmd, QualityCli& q);
// The radiance cache's options (part of add_quality_options; `bench peers` takes them alone).
void add_radiance_cache_options(CLI::App* cmd, RadianceCacheOptions& c);
// Validates and returns the options (throws std::invalid_argument on a bad value).
QualityOptions resolve_quality(const QualityCli& q);
// `--path-reuse VALUE` into o.path_reuse and o.path_reuse_auto (throws std::invalid_argument).
void parse_path_reuse(const std::string& value, QualityOptions& o);

}  // namespace tuneray
