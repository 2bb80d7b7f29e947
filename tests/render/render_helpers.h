// Shared by the render tests: one frame of `spp` samples per pixel on Embree's native BVH.
#pragma once

#include "accel/embree_native.h"
#include "image/image.h"
#include "render/film.h"
#include "render/sampler.h"
#include "render/tile_renderer.h"
#include "scene/builtins.h"
#include "scene/scene.h"

namespace tuneray::testing {

inline Film render_film(const Scene& scene, const RenderSettings& settings, const Sampler& sampler,
                        uint32_t spp, PassStats* stats = nullptr) {
  EmbreeNativeAccel accel;
  accel.build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
               scene.triangles.size()});
  TileRenderer renderer(scene, accel, scene.cameras.at(0), settings, sampler);
  Film film(settings.width, settings.height);
  PassStats pass = renderer.render_pass(film, 0, spp);
  if (stats) *stats = pass;
  return film;
}

inline Image render_image(const Scene& scene, const RenderSettings& settings,
                          const Sampler& sampler, uint32_t spp, PassStats* stats = nullptr) {
  return render_film(scene, settings, sampler, spp, stats).resolve();
}

// The PCG sampler seeded from the settings, as `tuneray render` uses it.
inline Image render_image(const Scene& scene, const RenderSettings& settings, uint32_t spp,
                          PassStats* stats = nullptr) {
  return render_image(scene, settings, PcgSampler(settings.seed), spp, stats);
}

// `passes` passes of one sample per pixel each, as `render` takes them (the radiance cache
// learns between passes), with the PCG sampler seeded from the settings; the cache's cell count
// goes to *cache_cells (0 without a cache) when asked.
inline Image render_in_passes(const Scene& scene, const RenderSettings& settings, uint32_t passes,
                              size_t* cache_cells = nullptr) {
  EmbreeNativeAccel accel;
  accel.build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
               scene.triangles.size()});
  const PcgSampler sampler(settings.seed);
  TileRenderer renderer(scene, accel, scene.cameras.at(0), settings, sampler);
  Film film(settings.width, settings.height);
  for (uint32_t i = 0; i < passes; ++i) renderer.render_pass(film, i, 1);
  if (cache_cells) {
    const RadianceCache* cache = renderer.integrator().radiance_cache();
    *cache_cells = cache ? cache->cells() : 0;
  }
  return film.resolve();
}

// The built-in Cornell box lit as Embree's pathtracer lights its own (bench peers): every
// surface Lambertian, no emitter, a point light below the ceiling. All of the noise is then in
// the walks beyond the first hit, where path reuse pays most.
inline Scene point_lit_box() {
  Scene scene = make_cornell_scene();
  for (Material& m : scene.materials) {
    m.type = MaterialType::kLambert;
    m.emission = Color(0.0f);
  }
  const BBox b = scene.bounds();
  const Vec3f centre = (b.lo + b.hi) * 0.5f, extent = b.hi - b.lo;
  scene.point_lights = {
      {Vec3f(centre.x, b.hi.y - 0.1f * extent.y, centre.z), Color(0.5f * extent.y * extent.y)}};
  return scene;
}

}  // namespace tuneray::testing
