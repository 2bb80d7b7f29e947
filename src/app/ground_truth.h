// Converged reference images for RMSE at equal time: rendered with every biasing option off and
// cached as EXR in a user-given folder, keyed by a hash of scene spec, camera, size, bounces
// and sample count.
#pragma once

#include <cstdint>
#include <string>

#include "accel/accel.h"
#include "image/image.h"
#include "scene/scene.h"

namespace tuneray {

struct GroundTruthKey {
  std::string scene_spec;  // as given to load_scene
  CameraDesc camera;
  int width = 0, height = 0;
  int max_bounces = 3;
  int spp = 4096;
};

// `dir`/truth-<hash>.exr; the hash covers every field of the key.
std::string ground_truth_path(const std::string& dir, const GroundTruthKey& key);

// Reads the cached image, or renders it (tiles, PCG sampler, seed 0, unbiased) and writes it.
// `rendered` (optional) tells which happened.
Image ground_truth(const std::string& dir, const GroundTruthKey& key, const Scene& scene,
                   const Accel& accel, bool* rendered = nullptr);

}  // namespace tuneray
