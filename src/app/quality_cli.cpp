#include "app/quality_cli.h"

#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>

#include "render/radiance_cache.h"

namespace tuneray {

void add_radiance_cache_options(CLI::App* cmd, RadianceCacheOptions& c) {
  cmd->add_option("--cache-vertex", c.vertex,
                  "Biased: paths end into a world-space radiance cache at this vertex (1 = the "
                  "second hit) on diffuse surfaces; 0 = off")
      ->check(CLI::Range(0, 1 << 16))
      ->capture_default_str();
  cmd->add_option("--cache-cell", c.cell,
                  "The radiance cache's cell side as a share of the scene's diagonal")
      ->check(CLI::Range(1.0f / 4096, 1.0f))
      ->capture_default_str();
  cmd->add_option("--cache-levels", c.levels,
                  "Levels of radiance cache cells, each half the side of the one before")
      ->check(CLI::Range(1, RadianceCache::kMaxLevels))
      ->capture_default_str();
  cmd->add_option("--cache-train", c.train,
                  "Share of the paths at a ready cache cell that go on and train it")
      ->check(CLI::Range(0.0f, 1.0f))
      ->capture_default_str();
  cmd->add_option("--cache-min-samples", c.min_samples,
                  "Training records a cache cell needs before paths end into it")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
}

void add_quality_options(CLI::App* cmd, QualityCli& q) {
  QualityOptions& o = q.options;
  cmd->add_option("--scheduler", q.scheduler,
                  "wavefront (paths in waves, batched rays) or tile (one path after another)")
      ->capture_default_str();
  cmd->add_option("--batch-size", o.batch_size, "Paths per wavefront wave")
      ->check(CLI::Range(1, 1 << 24))
      ->capture_default_str();
  cmd->add_option("--sky-texels", q.sky_texels, "Sky texel layout: rgba (16-byte) or rgb")
      ->capture_default_str();
  cmd->add_option("--sampler", q.sampler,
                  "Sample generator: pcg (white noise) or bluenoise (blue-noise screen-space "
                  "error up to 16 dimensions and 256 spp)")
      ->capture_default_str();
  cmd->add_option("--materials", q.materials,
                  "Material evaluation: branchless (f and pdf in one straight-line pass) or "
                  "by-type (a switch per material type)")
      ->capture_default_str();
  cmd->add_option("--sky-sampling", q.sky_sampling,
                  "Light samples of a constant sky: bsdf (directions drawn from the surface's "
                  "BSDF) or uniform (over the sphere)")
      ->capture_default_str();
  cmd->add_flag("!--no-one-texel", q.one_texel,
                "Keep textures on triangles whose UVs fall in one texel");
  cmd->add_flag("--lowres-sky", o.lowres_sky, "Biased: 8x8-averaged sky after the camera ray");
  cmd->add_flag("--regularize", o.regularize,
                "Biased: roughness never below the path's largest so far");
  cmd->add_option("--clamp", o.clamp, "Biased: max length of a path sample's RGB (0 = off)")
      ->check(CLI::Range(0.0f, 1e30f))
      ->capture_default_str();
  cmd->add_option("--clamp-rel", o.clamp_relative,
                  "Biased: clamp path samples to this many times the image's mean pixel length "
                  "(0 = off; the first pass is unclamped)")
      ->check(CLI::Range(0.0f, 1e30f))
      ->capture_default_str();
  cmd->add_flag("--denoise", o.denoise,
                "Biased: the written image is filtered by the edge-avoiding denoiser guided by "
                "first-hit albedo and normal (the film itself stays unbiased)");
  add_radiance_cache_options(cmd, o.cache);
  cmd->add_option("--path-reuse", q.path_reuse,
                  "Unbiased: pools of N neighbouring pixels share their paths' second vertices on "
                  "diffuse surfaces, each connected by a shadow ray: N = 2..64 in every pass, "
                  "off (or 0), or auto (pools of 16 in frame-budget mode while the render's own "
                  "passes show they pay; fixed --spp renders trace without). Needs "
                  "--max-bounces 2 or more and no --cache-vertex")
      ->capture_default_str();
  cmd->add_flag("--adaptive", q.adaptive_on,
                std::string("Adaptive sampling in frame-budget mode: extra samples where the "
                            "error is highest") +
                    (o.adaptive ? " (the default there)" : ""));
  cmd->add_flag("--no-adaptive", q.adaptive_off, "Uniform sampling in frame-budget mode");
  cmd->add_option("--adaptive-min-spp", o.adaptive_min_spp,
                  "Uniform samples per pixel before adaptive sampling starts")
      ->check(CLI::Range(2, 1 << 16))
      ->capture_default_str();
}

namespace {
// The value of a named choice, or an error that names the option, the value and the choices.
template <class T>
T choose(const char* option, const std::string& value,
         std::initializer_list<std::pair<const char*, T>> choices) {
  std::string names;
  for (const auto& [name, result] : choices) {
    if (value == name) return result;
    names += (names.empty() ? "" : " or ") + std::string(name);
  }
  throw std::invalid_argument(std::string("bad ") + option + " '" + value + "': expected " + names);
}
}  // namespace

QualityOptions resolve_quality(const QualityCli& q) {
  QualityOptions o = q.options;
  o.wavefront = choose<bool>("--scheduler", q.scheduler, {{"wavefront", true}, {"tile", false}});
  o.branchless_materials =
      choose<bool>("--materials", q.materials, {{"branchless", true}, {"by-type", false}});
  o.sky_rgba = choose<bool>("--sky-texels", q.sky_texels, {{"rgba", true}, {"rgb", false}});
  o.bsdf_sky = choose<bool>("--sky-sampling", q.sky_sampling, {{"bsdf", true}, {"uniform", false}});
  o.sampler = choose<SamplerKind>(
      "--sampler", q.sampler, {{"bluenoise", SamplerKind::kBlueNoise}, {"pcg", SamplerKind::kPcg}});
  if (q.adaptive_on && q.adaptive_off)
    throw std::invalid_argument("--adaptive and --no-adaptive contradict each other");
  if (q.adaptive_on) o.adaptive = true;
  if (q.adaptive_off) o.adaptive = false;
  parse_path_reuse(q.path_reuse, o);
  return o;
}

void parse_path_reuse(const std::string& value, QualityOptions& o) {
  o.path_reuse_auto = value == "auto";
  if (value == "off" || value == "0") {
    o.path_reuse = 0;
    return;
  }
  if (o.path_reuse_auto) {
    o.path_reuse = QualityOptions::kReusePool;
    return;
  }
  int pool = 0;
  size_t used = 0;
  try {
    pool = std::stoi(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != value.size() || pool < 2 || pool > 64)
    throw std::invalid_argument("bad --path-reuse '" + value +
                                "': expected off, auto or a pool size from 2 to 64");
  o.path_reuse = pool;
}

}  // namespace tuneray
