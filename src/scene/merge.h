// Combining several loaded meshes into one scene (JSON "meshes": [...]).
#pragma once

#include "scene/scene.h"

namespace tuneray {

// Appends the geometry, materials and textures of `part` to `into`, re-indexing vertices,
// material ids and texture references. Lights, environment and cameras of `part` are ignored.
void append_geometry(Scene& into, Scene&& part);

}  // namespace tuneray
