// bsdf_evaluate (one straight-line pass for every smooth material) against the per-type
// evaluation: same f and pdf to 1e-5 relative on random inputs. The per-type evaluation in turn
// gives exactly what bsdf_eval and bsdf_pdf give one after the other.
#include <gtest/gtest.h>

#include <cmath>

#include "math/rng.h"
#include "random_bsdf_inputs.h"
#include "render/bsdf.h"
#include "render/sampling.h"

namespace tuneray {
namespace {

using testing::random_color;
using testing::random_direction;

void expect_close(float a, float b, const char* what, MaterialType type, int trial) {
  EXPECT_LE(std::abs(a - b), 1e-5f * std::abs(b) + 1e-12f)
      << what << " of material " << static_cast<int>(type) << ", trial " << trial << ": " << a
      << " vs " << b;
}

constexpr MaterialType kTypes[] = {MaterialType::kLambert, MaterialType::kGlossy,
                                   MaterialType::kPrincipled, MaterialType::kMirror,
                                   MaterialType::kDielectric};

struct Case {
  BsdfParams p;
  Vec3f wo, wi;
};

Case random_case(Pcg32& rng, MaterialType type) {
  Case c;
  c.p.type = type;
  c.p.base_color = random_color(rng, 0.1f);
  c.p.specular_color = random_color(rng, 0.25f);  // principled without coat = Lambert
  // Roughness from below the clamp (1e-3) to 1, log-uniform.
  c.p.alpha_x = std::pow(10.0f, -4.0f + 4.0f * rng.next_float());
  c.p.alpha_y =
      rng.next_float() < 0.5f ? c.p.alpha_x : std::pow(10.0f, -4.0f + 4.0f * rng.next_float());
  c.wo = random_direction(rng);
  c.wi = random_direction(rng);
  if (rng.next_float() < 0.05f) c.wi = Vec3f(-c.wo.x, -c.wo.y, c.wo.z);  // the specular peak
  return c;
}

TEST(BsdfByType, IsExactlyEvalThenPdf) {
  Pcg32 rng(7, 3);
  int nonzero = 0;
  for (MaterialType type : kTypes)
    for (int trial = 0; trial < 20000; ++trial) {
      const Case c = random_case(rng, type);
      const BsdfEval e = bsdf_evaluate_by_type(c.p, c.wo, c.wi);
      const Color f = bsdf_eval(c.p, c.wo, c.wi);
      const float pdf = bsdf_pdf(c.p, c.wo, c.wi);
      ASSERT_EQ(e.f.x, f.x) << static_cast<int>(type) << ", trial " << trial;
      ASSERT_EQ(e.f.y, f.y) << static_cast<int>(type) << ", trial " << trial;
      ASSERT_EQ(e.f.z, f.z) << static_cast<int>(type) << ", trial " << trial;
      ASSERT_EQ(e.pdf, pdf) << static_cast<int>(type) << ", trial " << trial;
      nonzero += e.pdf > 0;
    }
  EXPECT_GT(nonzero, 12000);  // the three smooth types' lobes were covered, not only zeros
}

TEST(BsdfBranchless, AgreesWithThePerTypeEvaluation) {
  Pcg32 rng(21, 5);
  int nonzero[5] = {};
  for (int t = 0; t < 5; ++t)
    for (int trial = 0; trial < 20000; ++trial) {
      const Case c = random_case(rng, kTypes[t]);
      const BsdfParams& p = c.p;
      const Vec3f wo = c.wo, wi = c.wi;
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
