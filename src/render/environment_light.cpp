#include "render/environment_light.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace tuneray {

Vec2f EnvironmentLight::direction_to_uv(Vec3f d) {
  float theta = std::acos(std::clamp(d.y, -1.0f, 1.0f));
  float phi = std::atan2(d.x, -d.z);
  return {(phi + kPi) * (0.5f * kInvPi), theta * kInvPi};
}

Vec3f EnvironmentLight::uv_to_direction(Vec2f uv) {
  float phi = uv.x * 2.0f * kPi - kPi;
  float theta = uv.y * kPi;
  float sin_theta = std::sin(theta);
  return {sin_theta * std::sin(phi), std::cos(theta), -sin_theta * std::cos(phi)};
}

namespace {
TexelRgba to_rgba(Color c) {
  return {{c.x, c.y, c.z, 0.0f}};
}
Color from_rgba(const TexelRgba& t) {
  return {t.v[0], t.v[1], t.v[2]};
}
// Texel index of the map coordinates uv in a w x h equirectangular grid.
size_t texel_index(Vec2f uv, int w, int h) {
  int x = std::clamp(static_cast<int>(uv.x * w), 0, w - 1);
  int y = std::clamp(static_cast<int>(uv.y * h), 0, h - 1);
  return static_cast<size_t>(y) * w + x;
}
}  // namespace

EnvironmentLight::EnvironmentLight(const Environment& env, const EnvironmentOptions& options)
    : scale_(env.scale) {
  active_ = env.active() && env.scale > 0;
  if (!active_) return;
  if (env.map.empty()) {
    constant_ = env.constant * env.scale;
    mean_luminance_ = luminance(constant_);
    return;
  }
  map_ = &env.map;
  int w = map_->width(), h = map_->height();
  std::vector<float> weights(static_cast<size_t>(w) * h);
  double sum = 0, weight_sum = 0;
  for (int y = 0; y < h; ++y) {
    float sin_theta = std::sin(kPi * (y + 0.5f) / h);
    for (int x = 0; x < w; ++x) {
      float lum = std::max(0.0f, luminance(map_->at(x, y)));
      weights[static_cast<size_t>(y) * w + x] = lum * sin_theta;
      sum += lum * sin_theta;
      weight_sum += sin_theta;
    }
  }
  distribution_ = Distribution2D(weights, w, h);
  if (options.rgba_texels) {
    rgba_.resize(static_cast<size_t>(w) * h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        rgba_[static_cast<size_t>(y) * w + x] = to_rgba(map_->at(x, y) * scale_);
  }
  if (options.lowres) {
    lowres_width_ = (w + kLowresBlock - 1) / kLowresBlock;
    lowres_height_ = (h + kLowresBlock - 1) / kLowresBlock;
    lowres_.resize(static_cast<size_t>(lowres_width_) * lowres_height_);
    for (int by = 0; by < lowres_height_; ++by)
      for (int bx = 0; bx < lowres_width_; ++bx) {
        Color sum(0.0f);
        int n = 0;
        for (int y = by * kLowresBlock; y < std::min(h, (by + 1) * kLowresBlock); ++y)
          for (int x = bx * kLowresBlock; x < std::min(w, (bx + 1) * kLowresBlock); ++x, ++n)
            sum += map_->at(x, y);
        lowres_[static_cast<size_t>(by) * lowres_width_ + bx] =
            to_rgba(sum * (scale_ / static_cast<float>(std::max(n, 1))));
      }
  }
  mean_luminance_ = weight_sum > 0 ? static_cast<float>(sum / weight_sum) * scale_ : 0.0f;
  if (!(mean_luminance_ > 0)) active_ = false;
}

Color EnvironmentLight::texel_radiance(size_t texel) const {
  return rgba_.empty() ? map_->data()[texel] * scale_ : from_rgba(rgba_[texel]);
}

Color EnvironmentLight::eval(const EnvironmentLookup& at) const {
  if (!active_) return Color(0.0f);
  if (!map_) return constant_;
  return texel_radiance(texel_index(at.uv, map_->width(), map_->height()));
}

Color EnvironmentLight::eval_lowres(const EnvironmentLookup& at) const {
  if (lowres_.empty()) return eval(at);
  return from_rgba(lowres_[texel_index(at.uv, lowres_width_, lowres_height_)]);
}

EnvironmentSample EnvironmentLight::sample(Vec2f u) const {
  EnvironmentSample s;
  if (!active_) return s;
  if (!map_) {
    s.wi = sample_uniform_sphere(u);
    s.pdf = kUniformSpherePdf;
    s.radiance = constant_;
    return s;
  }
  float pdf_uv = 0;
  size_t texel = 0;
  Vec2f uv = distribution_.sample(u, &pdf_uv, &texel);
  float sin_theta = std::sin(uv.y * kPi);
  if (!(pdf_uv > 0) || !(sin_theta > 0)) return s;
  s.wi = uv_to_direction(uv);
  // Jacobian of the equirectangular map: d omega = 2 pi^2 sin(theta) du dv.
  s.pdf = pdf_uv / (2.0f * kPi * kPi * sin_theta);
  // The texel the pdf was taken from, not a lookup of s.wi (which would search the map again
  // and may round into the neighbour at a texel edge).
  s.radiance = texel_radiance(texel);
  return s;
}

float EnvironmentLight::pdf(const EnvironmentLookup& at) const {
  if (!active_) return 0.0f;
  if (!map_) return kUniformSpherePdf;
  // sin(theta) from cos(theta) = dir.y without the angle; (1 - y)(1 + y) keeps its precision
  // near the poles, where 1 - y * y cancels.
  const float y = std::clamp(at.dir.y, -1.0f, 1.0f);
  const float sin_theta = std::sqrt((1.0f - y) * (1.0f + y));
  if (!(sin_theta > 0)) return 0.0f;
  return distribution_.pdf(at.uv) / (2.0f * kPi * kPi * sin_theta);
}

}  // namespace tuneray
