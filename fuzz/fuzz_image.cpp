// Image files as textures, environment maps and `compare` read them: PFM, EXR, Radiance HDR,
// PNG, JPEG. A successful read must give a non-empty image of the size it reports.
#include <cstdint>
#include <exception>

#include "fuzz_files.h"
#include "image/io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tuneray;
  static const char* const kNames[] = {"in.pfm", "in.exr", "in.hdr", "in.png", "in.jpg"};
  const auto [variant, rest] = fuzz::select(data, size, 5);
  const std::string path = fuzz::write_file(kNames[variant], rest);
  try {
    Image image = read_image(path);
    if (image.empty() || image.width() <= 0 || image.height() <= 0 ||
        image.pixel_count() != static_cast<size_t>(image.width()) * image.height())
      __builtin_trap();
  } catch (const std::exception&) {
  }
  return 0;
}
