#include "bench/quality_configs.h"

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <vector>

namespace tuneray {

namespace {

struct Config {
  std::string name;
  std::function<void(QualitySwitches&, const QualityBenchOptions&)> apply;
};

void set_clamp(QualityOptions& o, const QualityBenchOptions& a) {
  o.clamp = a.clamp;
  o.clamp_relative = a.clamp > 0 ? 0.0f : a.clamp_relative;
}

// Path reuse's rows share second vertices in pools of QualityOptions::kReusePool pixels, on in
// every pass ("reuse") or where the render's own passes show it pays ("reuse-auto").
void set_reuse(QualityOptions& o, bool automatic = false) {
  o.path_reuse = QualityOptions::kReusePool;
  o.path_reuse_auto = automatic;
}

void set_unbiased(QualitySwitches& s) {
  QualityOptions& o = s.quality;
  o.wavefront = o.sky_rgba = o.branchless_materials = o.adaptive = o.bsdf_sky = true;
  o.sampler = SamplerKind::kBlueNoise;
  set_reuse(o, true);  // as the defaults: where it pays
  s.one_texel = true;
}

// What `render` does unless told otherwise: RenderSettings{} and one-texel folding.
void set_defaults(QualitySwitches& s) {
  s.quality = QualityOptions{};
  s.one_texel = true;
}

// The radiance cache's rows end paths at the second hit (RadianceCacheOptions::vertex).
constexpr int kBenchCacheVertex = 1;

using S = QualitySwitches;
using A = QualityBenchOptions;

// The baseline has every switch off (tiles, 12-byte sky texels, textures kept, per-type
// material evaluation, PCG numbers, a constant sky sampled uniformly, uniform sampling); each row
// switches one technique on; "unbiased" switches on every technique that leaves the expected image
// alone, "defaults" is QualityOptions{} (what the renderer does unless told otherwise, path
// reuse where it pays included), "defaults+denoise", "defaults+cache" and "defaults+reuse" are
// what turning the denoiser, the radiance cache or path reuse in every pass on by default would
// give, "defaults-reuse" the defaults without path reuse, "all" switches on every one (the cache
// then switches path reuse off).
const std::vector<Config>& configurations() {
  static const std::vector<Config> configs = {
      {"baseline", [](S&, const A&) {}},
      {"wavefront", [](S& s, const A&) { s.quality.wavefront = true; }},
      {"sky-rgba", [](S& s, const A&) { s.quality.sky_rgba = true; }},
      {"one-texel", [](S& s, const A&) { s.one_texel = true; }},
      {"branchless", [](S& s, const A&) { s.quality.branchless_materials = true; }},
      {"bluenoise", [](S& s, const A&) { s.quality.sampler = SamplerKind::kBlueNoise; }},
      {"bsdf-sky", [](S& s, const A&) { s.quality.bsdf_sky = true; }},
      {"adaptive", [](S& s, const A&) { s.quality.adaptive = true; }},
      {"lowres-sky", [](S& s, const A&) { s.quality.lowres_sky = true; }},
      {"regularize", [](S& s, const A&) { s.quality.regularize = true; }},
      {"clamp", [](S& s, const A& a) { set_clamp(s.quality, a); }},
      {"denoise", [](S& s, const A&) { s.quality.denoise = true; }},
      {"cache", [](S& s, const A&) { s.quality.cache.vertex = kBenchCacheVertex; }},
      {"reuse", [](S& s, const A&) { set_reuse(s.quality); }},
      {"reuse-auto", [](S& s, const A&) { set_reuse(s.quality, true); }},
      {"unbiased", [](S& s, const A&) { set_unbiased(s); }},
      {"defaults", [](S& s, const A&) { set_defaults(s); }},
      {"defaults+denoise",
       [](S& s, const A&) {
         set_defaults(s);
         s.quality.denoise = true;
       }},
      {"defaults+cache",
       [](S& s, const A&) {
         set_defaults(s);
         s.quality.cache.vertex = kBenchCacheVertex;
       }},
      {"defaults+reuse",
       [](S& s, const A&) {
         set_defaults(s);
         set_reuse(s.quality);
       }},
      {"defaults-reuse",
       [](S& s, const A&) {
         set_defaults(s);
         s.quality.path_reuse = 0;
       }},
      {"all",
       [](S& s, const A& a) {
         set_unbiased(s);
         s.quality.lowres_sky = s.quality.regularize = s.quality.denoise = true;
         s.quality.cache.vertex = kBenchCacheVertex;
         set_clamp(s.quality, a);
       }},
  };
  return configs;
}

}  // namespace

std::vector<std::string> quality_configurations() {
  std::vector<std::string> names;
  for (const Config& c : configurations()) names.push_back(c.name);
  return names;
}

void check_quality_configurations(const std::vector<std::string>& only) {
  const std::vector<std::string> known = quality_configurations();
  for (const std::string& name : only)
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      throw std::invalid_argument("bad --only '" + name + "': expected one of " + list);
    }
}

QualitySwitches quality_switches(const std::string& name, const QualityOptions& base,
                                 const QualityBenchOptions& options) {
  for (const Config& c : configurations())
    if (c.name == name) {
      QualitySwitches s{base, false};
      c.apply(s, options);
      return s;
    }
  throw std::invalid_argument("unknown quality configuration '" + name + "'");
}

}  // namespace tuneray
