// Everything that controls how a frame is rendered (not what is rendered).
#pragma once

#include <cstdint>

namespace tuneray {

enum class LightStrategy : uint8_t {
  kMis,        // next-event estimation + BSDF sampling, power heuristic (the default)
  kLightOnly,  // next-event estimation only (emitters hit by BSDF rays count only after deltas)
  kBsdfOnly,   // BSDF sampling only (point lights are then invisible)
};

struct RenderSettings {
  int width = 640;
  int height = 360;
  int max_bounces = 3;             // scattering events per path, as pbrt's maxdepth (1 = direct)
  int russian_roulette_depth = 3;  // bounces before Russian roulette may end a path
  int tile_size = 32;              // pixels per tile side (a work size the tuner may pick)
  uint64_t seed = 0;
  LightStrategy strategy = LightStrategy::kMis;
};

}  // namespace tuneray
