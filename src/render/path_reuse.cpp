#include "render/path_reuse.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "render/simd8.h"
#include "render/surface.h"

namespace tuneray {

float reuse_geometry(const ReuseVertices& from, const ReuseVertices& to) {
  const Vec3f d = to.p2 - from.p1;
  const float r2 = dot(d, d);
  if (!(r2 > 0.0f) || !std::isfinite(r2)) return 0.0f;
  const Vec3f dir = d * (1.0f / std::sqrt(r2));
  // The shading step keeps a direction only above both normals at x1 (cosine sampling about the
  // shading normal; a direction below the geometric one ends the path).
  const float cos1 = dot(from.n1, dir);
  if (!(cos1 > 0.0f) || !(dot(from.ng1, dir) > 0.0f)) return 0.0f;
  // x1 on the side of x2's surface that x2's walk shaded, and not where that side's shading
  // frame would be replaced by the geometric one (path_shade8.cpp's `below`): there the walk's
  // reflected radiance is the same in every direction it leaves in.
  const float cos2 = -dot(to.ng2, dir);
  if (!(cos2 > 0.0f) || !(-dot(to.ns2, dir) > 1e-6f)) return 0.0f;
  return cos1 * cos2 / r2;
}

void reuse_pools(std::span<const PixelSampleId> ids, int pool_pixels,
                 std::vector<uint32_t>& pool_slots, std::vector<uint32_t>& pool_begin) {
  pool_slots.clear();
  pool_begin.assign(1, 0);
  const size_t group = static_cast<size_t>(std::max(1, pool_pixels));
  std::vector<uint32_t> run_start, run_length;  // of the group's pixels
  auto flush = [&] {
    uint32_t longest = 0;
    for (const uint32_t n : run_length) longest = std::max(longest, n);
    for (uint32_t s = 0; s < longest; ++s) {
      const size_t before = pool_slots.size();
      for (size_t r = 0; r < run_start.size(); ++r)
        if (run_length[r] > s) pool_slots.push_back(run_start[r] + s);
      if (pool_slots.size() - before < 2)
        pool_slots.resize(before);
      else
        pool_begin.push_back(static_cast<uint32_t>(pool_slots.size()));
    }
    run_start.clear();
    run_length.clear();
  };
  for (size_t k = 0; k < ids.size(); ++k) {
    if (k > 0 && ids[k].x == ids[k - 1].x && ids[k].y == ids[k - 1].y) {
      ++run_length.back();
      continue;
    }
    if (run_start.size() == group) flush();
    run_start.push_back(static_cast<uint32_t>(k));
    run_length.push_back(1);
  }
  flush();
}

namespace {

// A pool's techniques as planes (padded to whole registers), for the pair loop.
struct Techniques {
  std::vector<uint32_t> slot;
  std::array<std::vector<float>, 12> plane;  // p1, n1, ng1, the shadow rays' origin (xyz each)
  enum { kP, kN = 3, kNg = 6, kOrigin = 9 };
  void clear() {
    slot.clear();
    for (auto& v : plane) v.clear();
  }
  void add(uint32_t s, const ReuseVertices& v) {
    slot.push_back(s);
    // The origin that offset_ray_origin gives every direction the pair loop keeps (those above
    // the geometric normal): the same for all of them.
    const Vec3f origin = offset_ray_origin(v.p1, v.ng1, v.ng1);
    const Vec3f rows[4] = {v.p1, v.n1, v.ng1, origin};
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 3; ++c) plane[static_cast<size_t>(3 * r + c)].push_back(rows[r][c]);
  }
  void pad() {
    while (slot.size() % simd::kLanes) {
      slot.push_back(UINT32_MAX);
      for (auto& v : plane) v.push_back(0.0f);  // a zero normal: no direction passes
    }
  }
  simd::V8 load(int row, size_t at) const {
    return {simd::F8::load(plane[static_cast<size_t>(row)].data() + at),
            simd::F8::load(plane[static_cast<size_t>(row + 1)].data() + at),
            simd::F8::load(plane[static_cast<size_t>(row + 2)].data() + at)};
  }
};

}  // namespace

uint64_t reuse_paths(const Accel& accel, std::span<const uint32_t> pool_slots,
                     std::span<const uint32_t> pool_begin, std::span<const ReuseVertices> vertices,
                     std::span<Color> indirect, PathReuseScratch& s) {
  using simd::F8;
  using simd::M8;
  using simd::V8;
  const size_t slots = vertices.size();
  s.sum.assign(slots, 0.0f);
  s.own.resize(slots);
  s.lr.resize(slots);
  s.gathered.assign(slots, Color(0.0f));
  s.shares.assign(slots, 0);
  s.rays.clear();
  s.from.clear();
  s.to.clear();
  s.geometry.clear();
  thread_local Techniques t;

  // Which second vertices are shared, their own technique's share of the denominator, and the
  // connections from every other technique of their pool, to be traced as one batch.
  for (size_t p = 0; p + 1 < pool_begin.size(); ++p) {
    t.clear();
    // A path whose value is invalid is dropped whole by finish(): it is no technique of its
    // pool either, which must not give its neighbours a share that then vanishes with it.
    for (uint32_t at = pool_begin[p]; at < pool_begin[p + 1]; ++at) {
      const uint32_t k = pool_slots[at];
      if (vertices[k].technique && is_finite(indirect[k])) t.add(k, vertices[k]);
    }
    const size_t members = t.slot.size();
    t.pad();
    for (size_t m = 0; m < members; ++m) {
      const uint32_t j = t.slot[m];
      const ReuseVertices& to = vertices[j];
      if (!to.shared) continue;
      const float own = reuse_geometry(to, to);
      Color lr;
      for (int c = 0; c < 3; ++c) lr[c] = (indirect[j][c] - to.l2[c]) / to.w1[c];
      if (!(own > 0.0f) || !is_finite(lr)) continue;
      s.shares[j] = 1;
      s.own[j] = s.sum[j] = own;
      s.lr[j] = lr;
      // reuse_geometry for eight techniques at a time.
      const V8 p2(to.p2), ng2(to.ng2), ns2(to.ns2);
      for (size_t k0 = 0; k0 < members; k0 += simd::kLanes) {
        const V8 d = p2 - t.load(Techniques::kP, k0);
        const F8 r2 = dot(d, d);
        const F8 inv_r = F8(1.0f) / simd::sqrt(r2);
        const V8 dir = d * inv_r;
        const F8 cos1 = dot(t.load(Techniques::kN, k0), dir);
        const F8 cos2 = -dot(ng2, dir);
        const M8 ok = (r2 > F8(0.0f)) & (r2 < F8(kInf)) & (cos1 > F8(0.0f)) &
                      (dot(t.load(Techniques::kNg, k0), dir) > F8(0.0f)) & (cos2 > F8(0.0f)) &
                      (-dot(ns2, dir) > F8(1e-6f));
        uint32_t bits = ok.bits();
        if (m >= k0 && m < k0 + simd::kLanes) bits &= ~(1u << (m - k0));
        if (!bits) continue;
        const F8 g = cos1 * cos2 / r2;
        const V8 origin = t.load(Techniques::kOrigin, k0);
        const F8 tfar = dot(p2 - origin, dir) * F8(1.0f - 1e-4f);
        alignas(32) float gs[simd::kLanes], tf[simd::kLanes], dx[simd::kLanes], dy[simd::kLanes],
            dz[simd::kLanes];
        g.store(gs), tfar.store(tf), dir.x.store(dx), dir.y.store(dy), dir.z.store(dz);
        for (; bits; bits &= bits - 1) {
          const int i = __builtin_ctz(bits);
          const size_t k = k0 + static_cast<size_t>(i);
          // Field by field into its place: a ray assembled on the stack and copied was read
          // back wider than it had been written, a store-forwarding stall per ray.
          Ray& ray = s.rays.emplace_back();
          ray.org.x = t.plane[Techniques::kOrigin][k];
          ray.org.y = t.plane[Techniques::kOrigin + 1][k];
          ray.org.z = t.plane[Techniques::kOrigin + 2][k];
          ray.dir.x = dx[i];
          ray.dir.y = dy[i];
          ray.dir.z = dz[i];
          ray.tnear = 0.0f;
          ray.tfar = tf[i];
          s.from.push_back(t.slot[k]);
          s.to.push_back(j);
          s.geometry.push_back(gs[i]);
        }
      }
    }
  }
  s.occluded.resize(s.rays.size());
  if (!s.rays.empty()) accel.occluded_batch(s.rays, s.occluded);

  // Balance heuristic: sum_k p_k(x2_j), with p_k proportional to geometry x visibility (the 1/pi
  // of the cosine pdf cancels against the Lambertian BSDF's).
  for (size_t c = 0; c < s.rays.size(); ++c)
    if (!s.occluded[c]) s.sum[s.to[c]] += s.geometry[c];
  for (size_t j = 0; j < slots; ++j)
    if (s.shares[j]) s.gathered[j] += vertices[j].w1 * s.lr[j] * (s.own[j] / s.sum[j]);
  for (size_t c = 0; c < s.rays.size(); ++c) {
    if (s.occluded[c]) continue;
    const uint32_t i = s.from[c], j = s.to[c];
    s.gathered[i] += vertices[i].w1 * s.lr[j] * (s.geometry[c] / s.sum[j]);
  }
  // The path's own walk beyond a shared x2 gives way to the pool's estimate; beyond any other x2
  // it stays. A path outside every pool gathered nothing.
  for (size_t i = 0; i < slots; ++i) {
    if (s.shares[i]) indirect[i] = vertices[i].l2;
    indirect[i] += s.gathered[i];
  }
  return s.rays.size();
}

}  // namespace tuneray
