#include "render/resource_limits.h"

#include <cstdint>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include "render/film.h"

namespace tuneray {

namespace {

// Bytes of MemAvailable, or 0 when unknown.
uint64_t available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key, unit;
  uint64_t kib = 0;
  while (meminfo >> key >> kib >> unit) {
    if (key == "MemAvailable:") return kib * 1024;
  }
  return 0;
}

}  // namespace

int clamp_threads(int requested) {
  const int machine = static_cast<int>(std::thread::hardware_concurrency());
  if (machine <= 0 || requested <= machine) return requested;
  std::cerr << "tuneray: note: --threads " << requested << " clamped to this machine's " << machine
            << " hardware threads\n";
  return machine;
}

void check_render_memory(int width, int height) {
  const uint64_t available = available_memory_bytes();
  const uint64_t needed =
      static_cast<uint64_t>(width) * static_cast<uint64_t>(height) * Film::kBytesPerPixelBound;
  if (available == 0 || needed <= available) return;
  std::ostringstream message;
  message << "image " << width << "x" << height << " needs about " << (needed >> 20)
          << " MiB, more than the " << (available >> 20) << " MiB this machine has available";
  throw std::invalid_argument(message.str());
}

}  // namespace tuneray
