// Google Benchmark kernels of the tuned BVH: the triangle tests and whole single-ray traversal
// per width / layout on a procedural triangle soup (the box tests dominate there).
#include <benchmark/benchmark.h>

#include <vector>

#include "accel/bvh_triangle.h"
#include "accel/embree_native.h"
#include "accel/tuned_bvh.h"
#include "math/rng.h"
#include "scene/scene.h"

namespace tuneray {
namespace {

struct Soup {
  std::vector<Vec3f> positions;
  std::vector<Triangle> triangles;
  std::vector<Ray> rays;
  GeometryView view() const {
    return {positions.data(), positions.size(), triangles.data(), triangles.size()};
  }
};

Vec3f random_vec(Pcg32& rng) {
  return {rng.next_float(), rng.next_float(), rng.next_float()};
}

const Soup& soup() {
  static const Soup s = [] {
    Soup out;
    Pcg32 rng(1);
    for (uint32_t i = 0; i < 200000; ++i) {
      Vec3f c = random_vec(rng);
      for (int k = 0; k < 3; ++k)
        out.positions.push_back(c + (random_vec(rng) - Vec3f(0.5f)) * 0.02f);
      out.triangles.push_back({{3 * i, 3 * i + 1, 3 * i + 2}});
    }
    for (int i = 0; i < 4096; ++i) {
      Vec3f o = random_vec(rng), d = normalize(random_vec(rng) - Vec3f(0.5f));
      out.rays.push_back({o, 0, d, kInf});
    }
    return out;
  }();
  return s;
}

bvh::TriPack4 random_pack(uint64_t seed) {
  bvh::TriPack4 pack{};
  Pcg32 rng(seed);
  for (int lane = 0; lane < 4; ++lane) {
    Vec3f a = random_vec(rng), b = random_vec(rng) - a, c = random_vec(rng) - a;
    const Vec3f rows[3] = {a, b, c};
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) pack.p[r * 3 + k][lane] = rows[r][k];
    }
  }
  return pack;
}

// Per-triangle cost of one pack with SSE against two packs in one AVX2 pass (items = triangles).
void BM_TrianglePackMT(benchmark::State& state) {
  const bvh::TriPack4 pack = random_pack(2);
  auto ray = bvh::make_traversal_ray(Vec3f(0.5f, 0.5f, -1), Vec3f(0, 0, 1), 0, kInf, false);
  bvh::LaneHits hits;
  for (auto _ : state) benchmark::DoNotOptimize(bvh::intersect_pack_mt(pack.p, ray, kInf, hits));
  state.SetItemsProcessed(state.iterations() * 4);
}
BENCHMARK(BM_TrianglePackMT);

void BM_TwoTrianglePacksMT(benchmark::State& state) {
  const bvh::TriPack4 a = random_pack(2), b = random_pack(4);
  auto ray = bvh::make_traversal_ray(Vec3f(0.5f, 0.5f, -1), Vec3f(0, 0, 1), 0, kInf, false);
  bvh::LaneHits hits;
  for (auto _ : state)
    benchmark::DoNotOptimize(bvh::intersect_two_packs_mt(a.p, b.p, ray, kInf, hits));
  state.SetItemsProcessed(state.iterations() * 8);
}
BENCHMARK(BM_TwoTrianglePacksMT);

void BM_TriangleWatertight(benchmark::State& state) {
  Pcg32 rng(3);
  Vec3f a = random_vec(rng), b = random_vec(rng), c = random_vec(rng);
  auto ray = bvh::make_traversal_ray(Vec3f(0.5f, 0.5f, -1), Vec3f(0, 0, 1), 0, kInf);
  bvh::TriangleHit hit;
  for (auto _ : state) benchmark::DoNotOptimize(bvh::intersect_watertight(a, b, c, ray, kInf, hit));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_TriangleWatertight);

void trace(benchmark::State& state, const Accel& accel) {
  const auto& rays = soup().rays;
  size_t i = 0;
  for (auto _ : state) {
    Hit h;
    benchmark::DoNotOptimize(accel.intersect(rays[i++ % rays.size()], h));
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_TraverseTuned(benchmark::State& state) {
  BvhConfig config;
  config.branching = static_cast<int>(state.range(0));
  config.compact = state.range(1) != 0;
  config.max_leaf = 4;
  TunedBvhAccel accel(config);
  accel.build(soup().view());
  trace(state, accel);
}
BENCHMARK(BM_TraverseTuned)->ArgsProduct({{2, 4, 8}, {0, 1}})->ArgNames({"width", "compact"});

void BM_TraverseNative(benchmark::State& state) {
  EmbreeNativeAccel accel;
  accel.build(soup().view());
  trace(state, accel);
}
BENCHMARK(BM_TraverseNative);

}  // namespace
}  // namespace tuneray

BENCHMARK_MAIN();
