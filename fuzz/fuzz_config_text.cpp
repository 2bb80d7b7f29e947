// The configuration texts users type or the database stores: `--bvh key=value,...` and the
// tuner's own configuration strings. What parses must print back to text that parses to the
// same value.
#include <cstdint>
#include <exception>
#include <string>

#include "accel/bvh_config.h"
#include "fuzz_files.h"
#include "tuning/bvh_space.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tuneray;
  const auto [variant, rest] = fuzz::select(data, size, 2);
  const std::string text(rest);
  try {
    if (variant == 0) {
      BvhConfig c = parse_bvh_config(text);
      if (!(parse_bvh_config(c.to_string()) == c)) __builtin_trap();
    } else {
      static const tuner::Space space = make_backend_space();
      tuner::Config c = space.parse(text);
      if (!(space.parse(c.to_string()) == c)) __builtin_trap();
    }
  } catch (const std::exception&) {
  }
  return 0;
}
