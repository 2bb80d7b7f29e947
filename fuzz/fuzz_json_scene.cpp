// JSON scene files (docs/scenes.md). A valid mesh and environment map sit next to the input, so
// inputs that name them reach the camera, light and material code.
#include <cstdint>
#include <exception>

#include "fuzz_files.h"
#include "scene/load.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tuneray;
  static const std::string mesh = fuzz::write_file(
      "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
  static const std::string sky = fuzz::write_file("sky.pfm", fuzz::one_texel_pfm());
  const std::string path = fuzz::write_file("in.json", fuzz::as_view(data, size));
  try {
    Scene scene = load_scene(path);
    if (scene.cameras.empty()) __builtin_trap();
  } catch (const std::exception&) {
  }
  return 0;
}
