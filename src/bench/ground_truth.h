// Converged reference images for RMSE at equal time: rendered with every biasing option off and
// cached as EXR in a user-given folder, keyed by a hash of scene spec, camera, size, bounces
// and sample count (or error target).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "accel/accel.h"
#include "image/image.h"
#include "render/render_settings.h"
#include "scene/scene.h"

namespace tuneray {

struct GroundTruthKey {
  std::string scene_spec;  // as given to load_scene
  CameraDesc camera;
  int width = 0, height = 0;
  int max_bounces = 3;
  int spp = 4096;         // samples per pixel (the most, when until_rmse > 0)
  double until_rmse = 0;  // > 0: stop once Film::estimated_rmse() is below it
  // Not part of the name: render again a cached truth written without its halves (before they
  // were kept), so that its own noise can be estimated (ground_truth_halves).
  bool require_halves = false;
};

// `dir`/truth-<hash>.exr; the hash covers every field of the key.
std::string ground_truth_path(const std::string& dir, const GroundTruthKey& key);

// The settings a ground truth is rendered with: QualityOptions::reference() (tiles, PCG,
// per-type materials, nothing biased) and seed 0. The equal-time renders use other seeds, so their
// noise is independent of the reference's.
RenderSettings ground_truth_settings(const GroundTruthKey& key);

struct GroundTruthInfo {
  bool rendered = false;  // false: read from the cache
  int spp = 0;            // samples per pixel rendered (0 when cached)
  double estimated_rmse = 0;
  double render_ms = 0;
};

// Called after every pass of a truth render with the samples per pixel it added and, when the key
// stops on an error target, the running RMSE estimate (else a negative value). The library draws
// nothing itself: the command line turns this into its progress bar.
using TruthProgress = std::function<void(int spp_added, double estimated_rmse)>;

// Reads the cached image, or renders it and writes it with its two halves (the film's even and
// odd samples) beside it.
Image ground_truth(const std::string& dir, const GroundTruthKey& key, const Scene& scene,
                   const Accel& accel, GroundTruthInfo* info = nullptr,
                   const TruthProgress& progress = {});

// `dir`/truth-<hash>.half0.exr and .half1.exr.
std::string ground_truth_half_path(const std::string& dir, const GroundTruthKey& key, int half);

// A truth's halves, each the mean of half its samples, independent of the other: what
// reference_noise_mse (image/metrics.h) estimates the truth's own noise from.
struct GroundTruthHalves {
  Image a, b;
};

// The cached halves; nullopt when either file is missing (a cache written before halves were
// kept). Throws std::runtime_error naming the file when one is unreadable or of another size.
std::optional<GroundTruthHalves> ground_truth_halves(const std::string& dir,
                                                     const GroundTruthKey& key);

}  // namespace tuneray
