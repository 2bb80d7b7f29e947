// Orthonormal frame for shading: local z is the normal, x/y the tangent directions
// (anisotropic GGX aligns its roughness with them).
#pragma once

#include <cmath>

#include "math/vec.h"

namespace tuneray {

struct Frame {
  Vec3f s, t, n;

  Frame() : s(1, 0, 0), t(0, 1, 0), n(0, 0, 1) {}
  Frame(Vec3f s_, Vec3f t_, Vec3f n_) : s(s_), t(t_), n(n_) {}

  // Branch-free basis from a unit normal (Duff et al. 2017, "Building an Orthonormal Basis,
  // Revisited").
  static Frame from_normal(Vec3f n) {
    float sign = std::copysign(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float b = n.x * n.y * a;
    return {Vec3f(1 + sign * n.x * n.x * a, sign * b, -sign * n.x),
            Vec3f(b, sign + n.y * n.y * a, -n.y), n};
  }
  // Frame whose s axis follows a tangent (Gram-Schmidt against n).
  static Frame from_normal_tangent(Vec3f n, Vec3f tangent) {
    Vec3f s = tangent - n * dot(n, tangent);
    float len = length(s);
    if (!(len > 1e-6f)) return from_normal(n);
    s = s / len;
    return {s, cross(n, s), n};
  }

  Vec3f to_local(Vec3f v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  Vec3f to_world(Vec3f v) const { return s * v.x + t * v.y + n * v.z; }
};

}  // namespace tuneray
