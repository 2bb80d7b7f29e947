// The eight-lane BSDFs, warps and light sampling of the SIMD shading step against the scalar
// functions they restate: on random inputs every lane gives the scalar value (to float rounding;
// the lanes use their own sine and cosine), and a lane's result does not depend on the others.
#include <gtest/gtest.h>

#include <cmath>

#include "math/rng.h"
#include "random_bsdf_inputs.h"
#include "render/bsdf.h"
#include "render/bsdf8.h"
#include "render/camera.h"
#include "render/environment_light.h"
#include "render/light_sampler.h"
#include "render/sampling.h"
#include "scene/load.h"

namespace tuneray {
namespace {

using simd::F8;
using simd::kLanes;
using simd::M8;
using simd::V8;

using testing::random_color;
using testing::random_direction;

BsdfParams random_smooth(Pcg32& rng) {
  constexpr MaterialType kSmooth[] = {MaterialType::kLambert, MaterialType::kGlossy,
                                      MaterialType::kPrincipled};
  BsdfParams p;
  p.type = kSmooth[rng.next_u32() % 3];
  p.base_color = random_color(rng, 0.1f);
  p.specular_color = random_color(rng, 0.25f);
  p.alpha_x = std::pow(10.0f, -4.0f + 4.0f * rng.next_float());
  p.alpha_y =
      rng.next_float() < 0.5f ? p.alpha_x : std::pow(10.0f, -4.0f + 4.0f * rng.next_float());
  return p;
}

struct Lanes {
  BsdfParams p[kLanes];
  Vec3f wo[kLanes], wi[kLanes];
  simd::SmoothBsdf8 bsdf;
  V8 wo8, wi8;
};

V8 lanes_of(const Vec3f (&v)[kLanes]) {
  alignas(32) float x[kLanes], y[kLanes], z[kLanes];
  for (int i = 0; i < kLanes; ++i) x[i] = v[i].x, y[i] = v[i].y, z[i] = v[i].z;
  return {F8::load(x), F8::load(y), F8::load(z)};
}

Lanes random_lanes(Pcg32& rng) {
  Lanes l;
  uint32_t lambert = 0, glossy = 0, principled = 0;
  Vec3f base[kLanes], spec[kLanes];
  alignas(32) float ax[kLanes], ay[kLanes];
  for (int i = 0; i < kLanes; ++i) {
    l.p[i] = random_smooth(rng);
    l.wo[i] = random_direction(rng);
    l.wi[i] = random_direction(rng);
    if (rng.next_float() < 0.05f) l.wi[i] = Vec3f(-l.wo[i].x, -l.wo[i].y, l.wo[i].z);
    const uint32_t bit = 1u << i;
    if (l.p[i].type == MaterialType::kLambert) lambert |= bit;
    if (l.p[i].type == MaterialType::kGlossy) glossy |= bit;
    if (l.p[i].type == MaterialType::kPrincipled) principled |= bit;
    base[i] = l.p[i].base_color;
    spec[i] = l.p[i].specular_color;
    ax[i] = std::max(l.p[i].alpha_x, simd::kMinAlpha8);
    ay[i] = std::max(l.p[i].alpha_y, simd::kMinAlpha8);
  }
  l.bsdf.lambert = M8::from_bits(lambert);
  l.bsdf.glossy = M8::from_bits(glossy);
  l.bsdf.principled = M8::from_bits(principled);
  l.bsdf.base = lanes_of(base);
  l.bsdf.specular = lanes_of(spec);
  l.bsdf.ax = F8::load(ax);
  l.bsdf.ay = F8::load(ay);
  l.wo8 = lanes_of(l.wo);
  l.wi8 = lanes_of(l.wi);
  return l;
}

void expect_close(float lane, float scalar, float rel, const std::string& what) {
  EXPECT_LE(std::abs(lane - scalar), rel * std::abs(scalar) + 1e-6f)
      << what << ": lane " << lane << " vs scalar " << scalar;
}

TEST(Bsdf8, EvaluateIsTheScalarEvaluationInEveryLane) {
  Pcg32 rng(11, 5);
  int nonzero = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    Lanes l = random_lanes(rng);
    simd::BsdfEval8 e = simd::evaluate(l.bsdf, l.wo8, l.wi8);
    for (int i = 0; i < kLanes; ++i) {
      BsdfEval s = bsdf_evaluate_by_type(l.p[i], l.wo[i], l.wi[i]);
      const std::string what = "trial " + std::to_string(trial) + " lane " + std::to_string(i) +
                               " type " + std::to_string(static_cast<int>(l.p[i].type));
      expect_close(e.f.lane(i).x, s.f.x, 1e-4f, what + " f.x");
      expect_close(e.f.lane(i).z, s.f.z, 1e-4f, what + " f.z");
      expect_close(e.pdf[i], s.pdf, 1e-4f, what + " pdf");
      nonzero += s.pdf > 0;
    }
  }
  EXPECT_GT(nonzero, 4000 * kLanes / 5);  // the test looked at real values, not zeros
}

TEST(Bsdf8, SampleIsTheScalarSampleInEveryLane) {
  Pcg32 rng(12, 9);
  int taken = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    Lanes l = random_lanes(rng);
    alignas(32) float ul[kLanes], u0[kLanes], u1[kLanes];
    for (int i = 0; i < kLanes; ++i)
      ul[i] = rng.next_float(), u0[i] = rng.next_float(), u1[i] = rng.next_float();
    simd::BsdfSample8 b = simd::sample(l.bsdf, l.wo8, F8::load(ul), F8::load(u0), F8::load(u1));
    for (int i = 0; i < kLanes; ++i) {
      BsdfSample s;
      const bool ok = bsdf_sample(l.p[i], l.wo[i], ul[i], {u0[i], u1[i]}, s);
      const std::string what = "trial " + std::to_string(trial) + " lane " + std::to_string(i) +
                               " type " + std::to_string(static_cast<int>(l.p[i].type));
      // Near the horizon a rounding difference may decide whether a sample exists.
      if (ok != (((b.ok.bits() >> i) & 1) != 0)) {
        EXPECT_LT(std::abs(s.wi.z), 1e-4f) << what;
        continue;
      }
      if (!ok) continue;
      ++taken;
      const Vec3f wi = b.wi.lane(i);
      // The lanes' own sine and cosine (4e-7) grow through the unstretching of the sharpest
      // GGX lobes (alpha 1e-3).
      EXPECT_LT(length(wi - s.wi), 1e-4f) << what;
      // Weights divide by pdfs that can be tiny for the sharpest lobes: relative tolerance.
      expect_close(b.pdf[i], s.pdf, 2e-3f, what + " pdf");
      expect_close(b.weight.lane(i).y, s.weight.y, 2e-3f, what + " weight");
    }
  }
  EXPECT_GT(taken, 4000 * kLanes / 3);  // wo is below the horizon half of the time
}

TEST(Bsdf8, SineAndCosineOfATurnMatchLibm) {
  for (int k = 0; k < 4096; k += 8) {
    alignas(32) float u[kLanes];
    for (int i = 0; i < kLanes; ++i) u[i] = (k + i) / 4096.0f;
    F8 s, c;
    simd::sincos_turn(F8::load(u), s, c);
    for (int i = 0; i < kLanes; ++i) {
      EXPECT_NEAR(s[i], std::sin(2.0 * M_PI * u[i]), 4e-7) << u[i];
      EXPECT_NEAR(c[i], std::cos(2.0 * M_PI * u[i]), 4e-7) << u[i];
    }
  }
}

TEST(Bsdf8, CosineHemisphereIsTheScalarWarp) {
  Pcg32 rng(3, 4);
  for (int trial = 0; trial < 2000; ++trial) {
    alignas(32) float u0[kLanes], u1[kLanes];
    for (int i = 0; i < kLanes; ++i) u0[i] = rng.next_float(), u1[i] = rng.next_float();
    if (trial == 0) u0[0] = u1[0] = 0.5f;  // the disk's centre
    const V8 w = simd::sample_cosine_hemisphere(F8::load(u0), F8::load(u1));
    for (int i = 0; i < kLanes; ++i)
      EXPECT_LT(length(w.lane(i) - sample_cosine_hemisphere({u0[i], u1[i]})), 1e-6f);
  }
}

TEST(Camera8, EveryLaneIsTheScalarCameraRay) {
  for (float lens_radius : {0.0f, 0.3f}) {
    CameraDesc desc;
    desc.position = {1, 2, 3};
    desc.target = {-2, 0.5f, -4};
    desc.vfov_deg = 50;
    desc.lens_radius = lens_radius;
    const Camera camera(desc, 320, 180);
    Pcg32 rng(8, 1);
    for (int trial = 0; trial < 200; ++trial) {
      alignas(32) float x[kLanes], y[kLanes], lu[kLanes], lv[kLanes];
      for (int i = 0; i < kLanes; ++i) {
        x[i] = 320 * rng.next_float(), y[i] = 180 * rng.next_float();
        lu[i] = rng.next_float(), lv[i] = rng.next_float();
      }
      V8 org, dir;
      camera.generate_rays8(F8::load(x), F8::load(y), F8::load(lu), F8::load(lv), org, dir);
      for (int i = 0; i < kLanes; ++i) {
        const Ray r = camera.generate_ray({x[i], y[i]}, {lu[i], lv[i]});
        EXPECT_LT(length(org.lane(i) - r.org), 1e-5f);
        EXPECT_LT(length(dir.lane(i) - r.dir), 1e-6f);
      }
    }
  }
}

// Area lights (the built-in Cornell box's lamp), point lights and the environment in one
// scene, so the light selection of sample8 crosses every kind.
TEST(LightSampler8, EveryLaneIsTheScalarSample) {
  for (const char* name : {"cornell", "sky", "voxels"}) {
    Scene scene = load_scene(name);
    scene.point_lights.push_back({Vec3f(0.1f, 0.9f, 0.2f), Color(3, 2, 1)});
    EnvironmentLight env(scene.environment);
    LightSampler lights(scene, env);
    const BBox b = scene.bounds();
    Pcg32 rng(21, 2);
    int lit = 0;
    for (int trial = 0; trial < 500; ++trial) {
      Vec3f p[kLanes];
      alignas(32) float u0[kLanes], u1[kLanes];
      for (int i = 0; i < kLanes; ++i) {
        p[i] = b.lo + (b.hi - b.lo) * Vec3f(rng.next_float(), rng.next_float(), rng.next_float());
        u0[i] = rng.next_float(), u1[i] = rng.next_float();
      }
      const uint32_t lanes = 0xffu >> (trial % 4);  // some calls leave lanes out
      LightSample8 ls = lights.sample8(lanes_of(p), F8::load(u0), F8::load(u1), lanes);
      for (int i = 0; i < kLanes; ++i) {
        if (!((lanes >> i) & 1)) continue;
        LightSample s = lights.sample(p[i], {u0[i], u1[i]});
        const std::string what =
            std::string(name) + " trial " + std::to_string(trial) + " lane " + std::to_string(i);
        expect_close(ls.pdf[i], s.pdf, 1e-4f, what + " pdf");
        // The number that placed the sample: u0 rescaled inside the light's share, as the
        // scalar selection rescales it.
        float pmf = 0, rescaled = 0;
        lights.selection().sample_discrete(u0[i], &pmf, &rescaled);
        EXPECT_NEAR(ls.u_in_light[i], rescaled, 1e-5f) << what;
        if (!(s.pdf > 0)) continue;
        ++lit;
        EXPECT_LT(length(ls.wi.lane(i) - s.wi), 1e-5f) << what;
        expect_close(ls.radiance.lane(i).x, s.radiance.x, 1e-4f, what + " radiance");
        expect_close(ls.distance[i], s.distance, 1e-5f, what + " distance");
        EXPECT_EQ(((ls.is_delta.bits() >> i) & 1) != 0, s.is_delta) << what;
      }
    }
    EXPECT_GT(lit, 1000) << name;
  }
}

}  // namespace
}  // namespace tuneray
