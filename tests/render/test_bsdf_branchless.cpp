// bsdf_evaluate (one straight-line pass for every smooth material) against the per-type
// bsdf_eval + bsdf_pdf it replaces: same f and pdf to 1e-5 relative on random inputs.
#include <gtest/gtest.h>

#include <cmath>

#include "math/rng.h"
#include "render/bsdf.h"
#include "render/sampling.h"

namespace tuneray {
namespace {

Vec3f random_direction(Pcg32& rng) {
  float z = 1.0f - 2.0f * rng.next_float();
  float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  float phi = 2.0f * kPi * rng.next_float();
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Color random_color(Pcg32& rng, float zero_chance) {
  if (rng.next_float() < zero_chance) return Color(0.0f);
  return Color(rng.next_float(), rng.next_float(), rng.next_float());
}

void expect_close(float a, float b, const char* what, MaterialType type, int trial) {
  EXPECT_LE(std::abs(a - b), 1e-5f * std::abs(b) + 1e-12f)
      << what << " of material " << static_cast<int>(type) << ", trial " << trial << ": " << a
      << " vs " << b;
}

TEST(BsdfBranchless, AgreesWithThePerTypeEvaluation) {
  Pcg32 rng(21, 5);
  const MaterialType types[] = {MaterialType::kLambert, MaterialType::kGlossy,
                                MaterialType::kPrincipled, MaterialType::kMirror,
                                MaterialType::kDielectric};
  int nonzero[5] = {};
  for (int t = 0; t < 5; ++t)
    for (int trial = 0; trial < 20000; ++trial) {
      BsdfParams p;
      p.type = types[t];
      p.base_color = random_color(rng, 0.1f);
      p.specular_color = random_color(rng, 0.25f);  // principled without coat = Lambert
      // Roughness from below the clamp (1e-3) to 1, log-uniform.
      p.alpha_x = std::pow(10.0f, -4.0f + 4.0f * rng.next_float());
      p.alpha_y =
          rng.next_float() < 0.5f ? p.alpha_x : std::pow(10.0f, -4.0f + 4.0f * rng.next_float());
      Vec3f wo = random_direction(rng), wi = random_direction(rng);
      if (rng.next_float() < 0.05f) wi = Vec3f(-wo.x, -wo.y, wo.z);  // the specular peak
      BsdfEval a = bsdf_evaluate(p, wo, wi);
      BsdfEval b = bsdf_evaluate_by_type(p, wo, wi);
      expect_close(a.f.x, b.f.x, "f.r", p.type, trial);
      expect_close(a.f.y, b.f.y, "f.g", p.type, trial);
      expect_close(a.f.z, b.f.z, "f.b", p.type, trial);
      expect_close(a.pdf, b.pdf, "pdf", p.type, trial);
      nonzero[t] += b.pdf > 0;
      if (::testing::Test::HasFailure()) return;
    }
  // The comparison covered the lobes (about a quarter of random pairs are both above).
  for (int t = 0; t < 3; ++t) EXPECT_GT(nonzero[t], 4000) << t;
}

}  // namespace
}  // namespace tuneray
