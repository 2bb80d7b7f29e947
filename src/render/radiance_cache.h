// A world-space radiance cache for diffuse surfaces: hashed grids of cells (position, the side
// of the surface, the material) that hold the mean of what the path tracer found beyond a
// vertex, so that later paths can end there (QualityOptions::cache). The idea is the one
// of path-space filtering and hashed radiance caches (Binder et al. 2019; NVIDIA's SHaRC): light
// deep in a path is smooth, so the noise of its random walk buys little, and a mean over nearby
// walks replaces it for the cost of a lookup. Biased: a cell averages over its extent. There are
// several levels of cells, each half the side of the one before; a lookup reads the finest cell
// that has enough records, so the cells shrink (and the bias with them) as records come in.
//
// What a cell stores does not depend on the direction the path arrived from: a Lambertian
// vertex reflects albedo times the cosine-weighted mean of what arrives, so the cell keeps that
// mean ("incident") and a path multiplies it by the albedo where it ends.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "math/bbox.h"
#include "math/vec.h"

namespace tuneray {

class RadianceCache {
 public:
  static constexpr int kMaxLevels = 4;

  // What one training path found beyond its cached vertex, with the key of its finest cell and
  // which pixel sample it was (so that records merge in one order whatever thread traced them).
  struct Record {
    uint64_t key = 0;
    uint32_t y = 0, x = 0, index = 0;
    Color incident{0.0f};  // NaN in a channel the path did not carry: no sample there
  };

  // The coarsest cells have side cell_fraction x the diagonal of `bounds`, and `levels` (1 to
  // kMaxLevels) levels of cells halve it; room for 2^capacity_log2 cells in all.
  RadianceCache(const BBox& bounds, float cell_fraction, int levels = 3, int capacity_log2 = 20);

  // The finest cell of point p on a surface whose normal n faces the arriving path, with
  // material m; 0 (no cell) where the point lies outside the bounds or the material id is too
  // large.
  uint64_t key(Vec3f p, Vec3f n, uint32_t material) const;
  // The mean incident term around p: of the finest cell with at least min_samples x 4^level
  // records in each channel (level 0: the coarsest), p
  // moved first by (j0, j1) of that cell's side (each in [-0.5, 0.5]) along the two axes that are
  // not the normal's dominant one. So jittered, a lookup reads a tent-filtered mean around p
  // instead of one cell's box, without the steps at cell borders.
  bool lookup(Vec3f p, Vec3f n, uint32_t material, float j0, float j1, int min_samples,
              Color& incident) const;
  // A lookup's jitter (j0, j1 in [-0.5, 0.5)) hashed from the point's bits: no sampler dimension
  // is spent on it, and it depends on nothing a scheduler chooses (which path slot, which thread).
  static void jitter(Vec3f p, float& j0, float& j1);
  // Adds the records to their cells at every level, sorted first so that the sums do not depend
  // on the order they came in. Not while lookups run. A full table takes no new cells.
  void add(std::vector<Record>& records);

  size_t cells() const { return used_; }
  int levels() const { return levels_; }
  float cell_size(int level) const;  // the side of a cell at that level (0: the coarsest)

 private:
  struct Entry {  // per channel: a record may be no sample in some (Record::incident)
    uint64_t key = 0;
    float sum[3] = {0, 0, 0};
    uint32_t count[3] = {0, 0, 0};
  };
  uint64_t key_at(Vec3f p, Vec3f n, uint32_t material, int level, float j0, float j1) const;
  size_t slot_of(uint64_t key) const;  // its entry, or the empty one where it would go

  Vec3f origin_;
  float finest_ = 1, inverse_finest_ = 1;  // the finest level's cell side
  int levels_ = 1;
  std::vector<Entry> table_;
  size_t mask_ = 0, used_ = 0;
};

}  // namespace tuneray
