// Mesh files: OBJ (with an MTL after a line "#mtl"), PLY, glTF, GLB, loaded and finalised as
// `render` does. A loader error is the expected outcome of most inputs; anything else that
// escapes (a crash, a sanitizer report, an invariant broken after a successful load) is a finding.
#include <cstdint>
#include <exception>
#include <string>

#include "fuzz_files.h"
#include "scene/load.h"

namespace {

void check_loaded(const tuneray::Scene& scene) {
  for (const auto& t : scene.triangles)
    for (uint32_t v : t.v)
      if (v >= scene.positions.size()) __builtin_trap();
  if (scene.material_ids.size() != scene.triangles.size()) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tuneray;
  // The texture the seed's MTL names, so texture loading is reached too.
  static const std::string texture = fuzz::write_file("tex.pfm", fuzz::one_texel_pfm());
  const auto [variant, rest] = fuzz::select(data, size, 4);
  std::string path;
  if (variant == 0) {
    const std::string_view marker = "\n#mtl\n";
    const size_t split = rest.find(marker);
    fuzz::write_file("in.mtl", split == std::string_view::npos
                                   ? std::string_view{}
                                   : rest.substr(split + marker.size()));
    path = fuzz::write_file("in.obj", rest.substr(0, split));
  } else {
    static const char* const kNames[] = {"", "in.ply", "in.gltf", "in.glb"};
    path = fuzz::write_file(kNames[variant], rest);
  }
  try {
    check_loaded(load_scene(path));
  } catch (const std::exception&) {
  }
  return 0;
}
