// A scene and native Embree's tree of it, built once: the set-up most rendering tests share.
#pragma once

#include <utility>

#include "accel/embree_native.h"
#include "scene/scene.h"

namespace tuneray::testing {

struct SceneWithNativeAccel {
  explicit SceneWithNativeAccel(Scene s) : scene(std::move(s)) {
    accel.build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
                 scene.triangles.size()});
  }
  Scene scene;
  EmbreeNativeAccel accel;
};

}  // namespace tuneray::testing
