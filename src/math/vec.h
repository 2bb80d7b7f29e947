// Small fixed-size vectors used everywhere: positions, directions, colours, UVs.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace tuneray {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 1.0f / kPi;
inline constexpr float kInf = 1e30f;

struct Vec2f {
  float x = 0, y = 0;
  constexpr Vec2f() = default;
  constexpr Vec2f(float x_, float y_) : x(x_), y(y_) {}
  constexpr Vec2f operator+(Vec2f o) const { return {x + o.x, y + o.y}; }
  constexpr Vec2f operator-(Vec2f o) const { return {x - o.x, y - o.y}; }
  constexpr Vec2f operator*(float s) const { return {x * s, y * s}; }
};

struct Vec3f {
  float x = 0, y = 0, z = 0;
  constexpr Vec3f() = default;
  constexpr explicit Vec3f(float s) : x(s), y(s), z(s) {}
  constexpr Vec3f(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}

  constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

  constexpr Vec3f operator-() const { return {-x, -y, -z}; }
  constexpr Vec3f operator+(Vec3f o) const { return {x + o.x, y + o.y, z + o.z}; }
  constexpr Vec3f operator-(Vec3f o) const { return {x - o.x, y - o.y, z - o.z}; }
  constexpr Vec3f operator*(Vec3f o) const { return {x * o.x, y * o.y, z * o.z}; }
  constexpr Vec3f operator/(Vec3f o) const { return {x / o.x, y / o.y, z / o.z}; }
  constexpr Vec3f operator*(float s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3f operator/(float s) const { return *this * (1.0f / s); }
  constexpr Vec3f& operator+=(Vec3f o) { return *this = *this + o; }
  constexpr Vec3f& operator-=(Vec3f o) { return *this = *this - o; }
  constexpr Vec3f& operator*=(Vec3f o) { return *this = *this * o; }
  constexpr Vec3f& operator*=(float s) { return *this = *this * s; }
  constexpr bool operator==(const Vec3f&) const = default;
};

constexpr Vec3f operator*(float s, Vec3f v) {
  return v * s;
}
constexpr float dot(Vec3f a, Vec3f b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3f cross(Vec3f a, Vec3f b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(Vec3f v) {
  return std::sqrt(dot(v, v));
}
inline Vec3f normalize(Vec3f v) {
  return v / length(v);
}
inline Vec3f min(Vec3f a, Vec3f b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
inline Vec3f max(Vec3f a, Vec3f b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
inline float max_component(Vec3f v) {
  return std::max(v.x, std::max(v.y, v.z));
}
inline float min_component(Vec3f v) {
  return std::min(v.x, std::min(v.y, v.z));
}
inline bool is_finite(Vec3f v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
// Rec. 709 luminance: used for light power, Russian roulette and firefly statistics.
constexpr float luminance(Vec3f c) {
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}
inline Vec3f lerp(Vec3f a, Vec3f b, float t) {
  return a * (1 - t) + b * t;
}
inline Vec3f reflect(Vec3f wo, Vec3f n) {
  return 2.0f * dot(wo, n) * n - wo;
}

using Color = Vec3f;

}  // namespace tuneray
