#include "render/radiance_cache.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <tuple>

namespace tuneray {

namespace {
// A key: 3 x 16 bits of cell, 3 of side (+1, so that no key is 0), 2 of level, 11 of material.
constexpr int kAxisBits = 16;
constexpr uint64_t kAxisMask = (uint64_t{1} << kAxisBits) - 1;
constexpr int kSideShift = 3 * kAxisBits, kLevelShift = kSideShift + 3, kMaterialShift = 53;
constexpr uint32_t kMaxMaterial = (1u << 11) - 1;
constexpr float kMaxCellIndex = static_cast<float>(kAxisMask);

uint64_t mix(uint64_t k) {  // splitmix64's finalizer: neighbouring cells to distant slots
  k ^= k >> 30;
  k *= 0xbf58476d1ce4e5b9ull;
  k ^= k >> 27;
  k *= 0x94d049bb133111ebull;
  return k ^ (k >> 31);
}

int dominant_axis(Vec3f n) {
  const Vec3f a{std::abs(n.x), std::abs(n.y), std::abs(n.z)};
  return a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
}
}  // namespace

RadianceCache::RadianceCache(const BBox& bounds, float cell_fraction, int levels,
                             int capacity_log2) {
  levels_ = std::clamp(levels, 1, kMaxLevels);
  const float diagonal = bounds.empty() ? 1.0f : std::max(bounds.diagonal(), 1e-6f);
  const float coarsest = std::clamp(cell_fraction, 1.0f / 4096, 1.0f) * diagonal;
  finest_ = std::ldexp(coarsest, -(levels_ - 1));
  inverse_finest_ = 1.0f / finest_;
  // Half a coarse cell of margin: points on the bounds' faces land inside.
  origin_ = (bounds.empty() ? Vec3f(0.0f) : bounds.lo) - Vec3f(0.5f * coarsest);
  table_.resize(size_t{1} << std::clamp(capacity_log2, 4, 28));
  mask_ = table_.size() - 1;
}

float RadianceCache::cell_size(int level) const {
  return std::ldexp(finest_, levels_ - 1 - std::clamp(level, 0, levels_ - 1));
}

uint64_t RadianceCache::key_at(Vec3f p, Vec3f n, uint32_t material, int level, float j0,
                               float j1) const {
  if (material > kMaxMaterial) return 0;
  const int axis = dominant_axis(n);
  // In units of the level's cells (level 0 the coarsest).
  Vec3f g = (p - origin_) * std::ldexp(inverse_finest_, -(levels_ - 1 - level));
  if (axis == 0) g += Vec3f(0, j0, j1);
  if (axis == 1) g += Vec3f(j0, 0, j1);
  if (axis == 2) g += Vec3f(j0, j1, 0);
  // NaN fails both comparisons, so it is refused as well.
  if (!(g.x >= 0 && g.y >= 0 && g.z >= 0 && g.x <= kMaxCellIndex && g.y <= kMaxCellIndex &&
        g.z <= kMaxCellIndex))
    return 0;
  // The side of the surface as the normal's dominant axis and its sign: the two faces of a thin
  // wall, or a box's faces meeting at an edge, never share a cell.
  const float along = axis == 0 ? n.x : (axis == 1 ? n.y : n.z);
  const uint64_t side = static_cast<uint64_t>(axis * 2 + (along < 0 ? 1 : 0));
  const auto cell = [](float v) { return static_cast<uint64_t>(v); };
  return cell(g.x) | cell(g.y) << kAxisBits | cell(g.z) << (2 * kAxisBits) |
         (side + 1) << kSideShift | static_cast<uint64_t>(level) << kLevelShift |
         static_cast<uint64_t>(material) << kMaterialShift;
}

uint64_t RadianceCache::key(Vec3f p, Vec3f n, uint32_t material) const {
  return key_at(p, n, material, levels_ - 1, 0, 0);
}

void RadianceCache::jitter(Vec3f p, float& j0, float& j1) {
  const uint64_t bits =
      mix((uint64_t{std::bit_cast<uint32_t>(p.x)} << 32 | std::bit_cast<uint32_t>(p.y)) ^
          uint64_t{std::bit_cast<uint32_t>(p.z)} << 16);
  j0 = static_cast<float>(bits & 0xffff) * 0x1p-16f - 0.5f;
  j1 = static_cast<float>((bits >> 16) & 0xffff) * 0x1p-16f - 0.5f;
}

size_t RadianceCache::slot_of(uint64_t key) const {
  size_t i = mix(key) & mask_;
  while (table_[i].key != 0 && table_[i].key != key) i = (i + 1) & mask_;
  return i;
}

bool RadianceCache::lookup(Vec3f p, Vec3f n, uint32_t material, float j0, float j1, int min_samples,
                           Color& incident) const {
  for (int level = levels_ - 1; level >= 0; --level) {
    const uint64_t key = key_at(p, n, material, level, j0, j1);
    if (key == 0) return false;
    // A cell a quarter of the area needs four times the records: a finer cell is read once its
    // mean is as certain as its parent's was when that was first read.
    const uint32_t enough = static_cast<uint32_t>(std::max(1, min_samples)) << (2 * level);
    const Entry& e = table_[slot_of(key)];
    if (e.key != key || std::min({e.count[0], e.count[1], e.count[2]}) < enough) continue;
    incident =
        Color(e.sum[0] / static_cast<float>(e.count[0]), e.sum[1] / static_cast<float>(e.count[1]),
              e.sum[2] / static_cast<float>(e.count[2]));
    return true;
  }
  return false;
}

void RadianceCache::add(std::vector<Record>& records) {
  std::sort(records.begin(), records.end(), [](const Record& a, const Record& b) {
    return std::tie(a.key, a.y, a.x, a.index) < std::tie(b.key, b.y, b.x, b.index);
  });
  // At most three quarters full: linear probing stays short.
  const size_t limit = table_.size() / 4 * 3;
  const uint64_t cell_bits = (uint64_t{1} << kSideShift) - 1;
  for (const Record& r : records) {
    const float v[3] = {r.incident.x, r.incident.y, r.incident.z};
    if (r.key == 0 || !(std::isfinite(v[0]) || std::isfinite(v[1]) || std::isfinite(v[2])))
      continue;
    const uint64_t rest = r.key & ~cell_bits & ~(uint64_t{3} << kLevelShift);
    for (int level = levels_ - 1; level >= 0; --level) {
      // A coarser level's cell holds 2 x 2 x 2 of the next finer one's.
      const int shift = levels_ - 1 - level;
      const uint64_t x = (r.key & kAxisMask) >> shift;
      const uint64_t y = ((r.key >> kAxisBits) & kAxisMask) >> shift;
      const uint64_t z = ((r.key >> (2 * kAxisBits)) & kAxisMask) >> shift;
      const uint64_t key = x | y << kAxisBits | z << (2 * kAxisBits) | rest |
                           static_cast<uint64_t>(level) << kLevelShift;
      Entry& e = table_[slot_of(key)];
      if (e.key == 0) {
        if (used_ >= limit) continue;
        e.key = key;
        ++used_;
      }
      for (int c = 0; c < 3; ++c)
        if (std::isfinite(v[c])) {
          e.sum[c] += v[c];
          ++e.count[c];
        }
    }
  }
  records.clear();
}

}  // namespace tuneray
