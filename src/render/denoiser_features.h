// The denoiser's guides: per pixel, the albedo and shading normal of the first surface the
// camera sees through mirrors. They are noise-free up to antialiasing, so edges in them are
// edges of the scene, not of the noise. One small pass of camera rays computes them once per
// film (the camera does not move while a film accumulates), so the path tracer's hot loop
// and both schedulers stay untouched, and the guides are the same whichever scheduler runs.
#pragma once

#include <cstdint>
#include <vector>

#include "image/image.h"
#include "render/tile_renderer.h"

namespace tuneray {

struct DenoiseFeatures {
  int width = 0, height = 0;
  // Rows of width pixels. Albedo is 1 where the camera sees the sky, a light or glass (the
  // filter must not divide their radiance by a surface colour); the normal faces the camera
  // (-direction where it sees the sky, so neighbouring sky pixels agree) and has unit length.
  std::vector<Color> albedo;
  std::vector<Vec3f> normal;
  // 1 where a feature ray saw a light (directly or through mirrors): radiance there is not
  // the surface's reflected light but an emitter's, often partly covering the pixel. Empty:
  // none anywhere.
  std::vector<uint8_t> emitter;
  // How much of the direct light reaches the first surface: the fraction of its next-event
  // samples' unshadowed contribution that is not occluded, in [0, 1], and that fraction's
  // variance (of the mean over the pixel's samples). Shadow edges, which neither albedo nor
  // normal shows, are edges here; hard ones (point lights, small lights) are noise-free.
  // Where no light reaches a surface it is 0; sky, lights and glass have 1. Empty: the scene
  // has no lights, so no guide.
  std::vector<float> visibility, visibility_variance;
  // The mean of the first surfaces' positions (through mirrors), far along the ray where the
  // camera sees the sky. Two surfaces with the same albedo and normal at different depths (a
  // box's face before a wall) differ here. Empty: no guide.
  std::vector<Vec3f> position;
  // 1 where the pixel's feature rays disagree (an edge, a texture, a shadow's edge, a light
  // partly covering it) or its features differ from a neighbour's (an edge between its rays and
  // its border): only there can more rays change the features.
  std::vector<uint8_t> detail;
};

// Camera rays per pixel side for the features (antialiased edges), stratified. With 2 x 2 the
// albedo of finely textured or detailed views (lost-empire from afar) is a noisy estimate of
// the pixel's, and the filter's output carries that error at every sample count; 4 x 4 costs
// four times as much, which at the shortest budgets (a quarter second) outweighs it. So
// FrameResolver starts with 2 x 2 and renders 4 x 4 once the film has some samples.
inline constexpr int kFeatureRaysPerSide = 4;
inline constexpr int kFirstFeatureRaysPerSide = 2;

// Light samples per pixel for the visibility guide, spread over its feature rays (at least one
// each): 8 for 2 x 2 rays, 16 for 4 x 4.
inline constexpr int visibility_samples_per_ray(int rays_per_side) {
  return rays_per_side * rays_per_side >= 8 ? 1 : 8 / (rays_per_side * rays_per_side);
}

// The features of the renderer's scene, camera and resolution, from rays_per_side^2 camera rays
// a pixel (1 to kFeatureRaysPerSide; std::invalid_argument otherwise). With `coarse` (features
// of the same view from fewer rays), only its detail pixels are traced again; the others keep the
// coarse features, since rays that all agree with each other and with the neighbours' leave
// nothing to refine (docs/quality.md, "Twenty-seventh session").
// std::invalid_argument when `coarse` is of another size.
DenoiseFeatures render_denoise_features(const TileRenderer& renderer,
                                        int rays_per_side = kFeatureRaysPerSide,
                                        const DenoiseFeatures* coarse = nullptr);

}  // namespace tuneray
