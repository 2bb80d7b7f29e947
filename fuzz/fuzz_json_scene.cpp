// JSON scene files (docs/scenes.md). A valid mesh and environment map sit next to the input, so
// inputs that name them reach the camera, light and material code.
#include <cstdint>
#include <exception>

#include "fuzz_files.h"
#include "scene/load.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tuneray;
  static const bool prepared = [] {
    fuzz::write_file("tri.obj",
                     "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
    const float texel[3] = {0.5f, 0.25f, 1.0f};
    std::string pfm = "PF\n1 1\n-1.0\n";
    pfm.append(reinterpret_cast<const char*>(texel), sizeof texel);
    fuzz::write_file("sky.pfm", pfm);
    return true;
  }();
  (void)prepared;
  const std::string path = fuzz::write_file("in.json", fuzz::as_view(data, size));
  try {
    Scene scene = load_scene(path);
    if (scene.cameras.empty()) __builtin_trap();
  } catch (const std::exception&) {
  }
  return 0;
}
