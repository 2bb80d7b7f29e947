// The environment as a light: a constant colour or an equirectangular map, importance sampled
// by luminance x sin(theta). Convention: +y is up; v = theta / pi (row 0 = straight up);
// u = (atan2(x, -z) + pi) / (2 pi), so the centre of the image is the direction -z.
#pragma once

#include <vector>

#include "image/image.h"
#include "math/vec.h"
#include "render/sampling.h"
#include "scene/scene.h"

namespace tuneray {

struct EnvironmentSample {
  Vec3f wi;
  Color radiance{0.0f};
  float pdf = 0;  // solid angle
};

// One texel as four floats on a 16-byte boundary: a lookup is one aligned load (the fourth
// lane is padding).
struct alignas(16) TexelRgba {
  float v[4];
};

// Where a direction meets the map, found once for both eval() and pdf() of that direction (a
// miss needs both, and the search costs an acos and an atan2).
struct EnvironmentLookup {
  Vec3f dir;
  Vec2f uv;
};

struct EnvironmentOptions {
  bool rgba_texels = true;  // look texels up in an aligned RGBA copy (else the 12-byte Image)
  bool lowres = false;      // also build the 8x8-block-averaged map for eval_lowres()
};

// Side of the texel blocks averaged into one low-resolution texel.
inline constexpr int kLowresBlock = 8;

class EnvironmentLight {
 public:
  EnvironmentLight() = default;
  explicit EnvironmentLight(const Environment& env, const EnvironmentOptions& options = {});

  bool active() const { return active_; }
  // An active environment of one colour (no map): its radiance is constant() everywhere and its
  // sampling uniform over the sphere, which the SIMD shading step does eight lanes at a time.
  bool is_constant() const { return active_ && !map_; }
  const Color& constant() const { return constant_; }
  static EnvironmentLookup locate(Vec3f dir) { return {dir, direction_to_uv(dir)}; }
  Color eval(Vec3f dir) const { return eval(lookup(dir)); }
  Color eval(const EnvironmentLookup& at) const;
  // The map averaged over 8x8 texel blocks (biased; for rays after the first bounce). Falls back
  // to eval() when the low-resolution map was not requested.
  Color eval_lowres(Vec3f dir) const { return eval_lowres(lookup(dir)); }
  Color eval_lowres(const EnvironmentLookup& at) const;
  EnvironmentSample sample(Vec2f u) const;
  float pdf(Vec3f dir) const { return pdf(lookup(dir)); }
  float pdf(const EnvironmentLookup& at) const;
  // Average radiance, for the light-selection weight.
  float mean_luminance() const { return mean_luminance_; }

  static Vec2f direction_to_uv(Vec3f dir);
  static Vec3f uv_to_direction(Vec2f uv);

 private:
  // locate(dir) where there is a map; a constant environment needs no map coordinates.
  EnvironmentLookup lookup(Vec3f dir) const {
    return map_ ? locate(dir) : EnvironmentLookup{dir, {}};
  }
  // Radiance of texel y * width + x of the map (scaled).
  Color texel_radiance(size_t texel) const;

  bool active_ = false;
  Color constant_{0.0f};
  const Image* map_ = nullptr;
  std::vector<TexelRgba> rgba_;  // map_ as aligned RGBA, pre-scaled; empty when not requested
  std::vector<TexelRgba> lowres_;
  int lowres_width_ = 0, lowres_height_ = 0;
  float scale_ = 1.0f;
  Distribution2D distribution_;
  float mean_luminance_ = 0;
};

}  // namespace tuneray
