// Embree's own choices of triangle BVH and builder (`tri_accel`, `tri_builder`), which it reads
// per device: every accepted one must build, trace single rays and batches, and find what
// Embree's default finds; names Embree cannot run and combinations it would silently ignore are
// refused before Embree sees them.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "accel/embree_native.h"
#include "accel/factory.h"
#include "batch_check.h"
#include "compare_backends.h"
#include "test_geometry.h"

namespace tuneray::test {
namespace {

constexpr size_t kRaysPerKind = 5000;

void expect_same_as_default(const std::string& params) {
  SCOPED_TRACE("native " + params);
  const Mesh mesh = make_icosphere(4);
  const GeometryView g = mesh.view();
  EmbreeNativeAccel reference;
  reference.build(g);
  const auto accel = make_accel("native", params);
  accel->build(g);
  EXPECT_NE(accel->describe().find(params), std::string::npos) << accel->describe();
  const RaySets rays = make_ray_sets(g, kRaysPerKind, 7);
  const Agreement a = compare(*accel, reference, rays, g);
  SCOPED_TRACE(a.summary());
  EXPECT_GT(a.hits, kRaysPerKind / 10);
  // Another BVH and triangle test may decide a ray grazing an edge the other way: one in 5,000.
  EXPECT_LE(a.hit_mismatch, a.rays / 5000);
  EXPECT_LE(a.shadow_mismatch, a.rays / 5000);
  EXPECT_EQ(a.dist_mismatch, 0u);
  // The batch entry points go through Embree's stream intersectors, which the quantized BVHs
  // lack; they must exist and agree with the single-ray calls (to rounding: Embree's stream and
  // single-ray triangle tests need not round alike on every CPU).
  for (RayCoherence coherence : {RayCoherence::kCoherent, RayCoherence::kIncoherent})
    expect_batch_hits_match_single_ray_hits(*accel, rays.closest, coherence);
}

TEST(NativeDeviceChoices, EveryAcceptedTriangleBvhFindsWhatTheDefaultFinds) {
  for (const std::string& name : native_tri_accels()) expect_same_as_default("tri_accel=" + name);
}

TEST(NativeDeviceChoices, EveryAcceptedBuilderFindsWhatTheDefaultFinds) {
  for (const std::string& name : native_tri_builders())
    expect_same_as_default("tri_builder=" + name);
}

TEST(NativeDeviceChoices, UnknownNamesAndIgnoredCombinationsAreRefused) {
  for (const char* params :
       {"tri_accel=qbvh8.triangle4", "tri_accel=bvh16.triangle4", "tri_builder=morton",
        "tri_accel=bvh4.triangle4,robust=1", "tri_accel=bvh4.triangle4,quality=high",
        "tri_builder=sah,compact=1", "tri_builder=sah,dynamic=1"}) {
    SCOPED_TRACE(params);
    EXPECT_THROW(make_accel("native", params), std::invalid_argument);
  }
  // Options made in code rather than parsed are checked when the scene is built.
  NativeOptions options;
  options.tri_accel = "bvh8.triangle4v";
  options.robust = true;
  EmbreeNativeAccel accel(options);
  const Mesh mesh = make_icosphere(1);
  EXPECT_THROW(accel.build(mesh.view()), BuildError);
}

TEST(NativeDeviceChoices, OneDevicePerConfigurationWhileItIsHeld) {
  const auto a = EmbreeDevice::shared("tri_accel=bvh4.triangle4");
  const auto b = EmbreeDevice::shared("tri_accel=bvh4.triangle4");
  const auto c = EmbreeDevice::shared("tri_accel=bvh8.triangle4v");
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  EXPECT_EQ(EmbreeDevice::shared(""), EmbreeDevice::shared());
  EXPECT_NE(a, EmbreeDevice::shared());
}

}  // namespace
}  // namespace tuneray::test
