// Material evaluation as the integrator's next-event estimation does it (f and pdf of a light
// direction): the per-type bsdf_eval + bsdf_pdf against the one-pass bsdf_evaluate, on one
// material type at a time and on a random mix (where type branches mispredict).
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "math/rng.h"
#include "render/bsdf.h"

namespace tuneray {
namespace {

struct Query {
  BsdfParams p;
  Vec3f wo, wi;
};

Vec3f upper_direction(Pcg32& rng) {
  float z = 0.05f + 0.95f * rng.next_float();
  float r = std::sqrt(1.0f - z * z);
  float phi = 6.2831853f * rng.next_float();
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// mix < 0: random smooth types; else that MaterialType.
std::vector<Query> make_queries(int type) {
  Pcg32 rng(11, 3);
  std::vector<Query> q(4096);
  for (Query& x : q) {
    int t = type >= 0 ? type : static_cast<int>(rng.next_u32() % 3);
    x.p.type = t == 0   ? MaterialType::kLambert
               : t == 1 ? MaterialType::kGlossy
                        : MaterialType::kPrincipled;
    x.p.base_color = Color(rng.next_float(), rng.next_float(), rng.next_float());
    x.p.specular_color = Color(0.04f + 0.5f * rng.next_float());
    x.p.alpha_x = x.p.alpha_y = 0.05f + 0.5f * rng.next_float();
    x.wo = upper_direction(rng);
    x.wi = upper_direction(rng);
  }
  return q;
}

template <BsdfEval (*Evaluate)(const BsdfParams&, Vec3f, Vec3f)>
void BM_Evaluate(benchmark::State& state) {
  std::vector<Query> queries = make_queries(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    float sum = 0;
    for (const Query& x : queries) {
      BsdfEval e = Evaluate(x.p, x.wo, x.wi);
      sum += e.f.x + e.pdf;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(queries.size()));
}

// Arg: -1 = random mix, 0 = Lambert, 1 = glossy, 2 = principled.
BENCHMARK(BM_Evaluate<bsdf_evaluate_by_type>)->Name("per_type")->Arg(-1)->Arg(0)->Arg(1)->Arg(2);
BENCHMARK(BM_Evaluate<bsdf_evaluate>)->Name("one_pass")->Arg(-1)->Arg(0)->Arg(1)->Arg(2);

}  // namespace
}  // namespace tuneray

BENCHMARK_MAIN();
