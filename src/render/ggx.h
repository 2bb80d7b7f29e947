// Anisotropic GGX (Trowbridge-Reitz) microfacet distribution with the Smith masking function.
// References: Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based
// BRDFs"; Heitz 2018, "Sampling the GGX Distribution of Visible Normals".
// Inline: they run several times per path vertex, and as out-of-line calls they were 12 % of a
// conference frame's samples on their own (docs/quality.md, "A faster sample").
#pragma once

#include <algorithm>
#include <cmath>

#include "math/vec.h"

namespace tuneray::ggx {

inline float D(Vec3f wh, float ax, float ay) {
  if (wh.z <= 0) return 0.0f;
  // For a unit wh: cos^4 (1 + tan^2 (cos^2 phi / ax^2 + sin^2 phi / ay^2))^2 equals this square.
  float x = wh.x / ax, y = wh.y / ay;
  float s = x * x + y * y + wh.z * wh.z;
  return 1.0f / (kPi * ax * ay * s * s);
}

inline float Lambda(Vec3f w, float ax, float ay) {
  float z2 = w.z * w.z;
  if (z2 <= 0) return kInf;
  float t = (ax * ax * w.x * w.x + ay * ay * w.y * w.y) / z2;  // alpha^2 tan^2 theta
  return 0.5f * (std::sqrt(1.0f + t) - 1.0f);
}

inline float G1(Vec3f w, float ax, float ay) {
  return 1.0f / (1.0f + Lambda(w, ax, ay));
}

inline float G2(Vec3f wo, Vec3f wi, float ax, float ay) {
  // Height-correlated form: masking and shadowing are not independent (tall microfacets pass
  // both), which is less dark at grazing angles than G1(wo) G1(wi).
  return 1.0f / (1.0f + Lambda(wo, ax, ay) + Lambda(wi, ax, ay));
}

// Samples a visible normal (Heitz 2018) for wo in the upper hemisphere; pdf of wh is
// G1(wo) max(0, wo.wh) D(wh) / wo.z.
inline Vec3f sample_visible_normal(Vec3f wo, float ax, float ay, Vec2f u) {
  // Stretch to the configuration where the distribution is a hemisphere, sample the projected
  // area of the visible hemisphere, and unstretch.
  Vec3f vh = normalize(Vec3f(ax * wo.x, ay * wo.y, wo.z));
  float len2 = vh.x * vh.x + vh.y * vh.y;
  Vec3f t1 = len2 > 0 ? Vec3f(-vh.y, vh.x, 0) / std::sqrt(len2) : Vec3f(1, 0, 0);
  Vec3f t2 = cross(vh, t1);
  float r = std::sqrt(u.x);
  float phi = 2.0f * kPi * u.y;
  float p1 = r * std::cos(phi);
  float p2 = r * std::sin(phi);
  float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * p2;
  Vec3f nh = t1 * p1 + t2 * p2 + vh * std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2));
  return normalize(Vec3f(ax * nh.x, ay * nh.y, std::max(1e-7f, nh.z)));
}

}  // namespace tuneray::ggx
