#include "app/resource_limits.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "render/film.h"

namespace tuneray {

namespace {

bool reads_as_non_finite(const std::string& text) {
  if (text.empty()) return false;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && !std::isfinite(v);
}

void add_finite_check(CLI::App& app, const CLI::Validator& finite) {
  for (CLI::Option* option : app.get_options()) {
    if (option->get_expected_min() > 0) option->check(finite);
  }
  for (CLI::App* sub : app.get_subcommands({})) add_finite_check(*sub, finite);
}

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

void refuse_non_finite_numbers(CLI::App& app) {
  const CLI::Validator finite(
      [](std::string& value) {
        return reads_as_non_finite(value) ? "'" + value + "' is not a finite number"
                                          : std::string();
      },
      "");
  add_finite_check(app, finite);
}

int clamp_threads(int requested) {
  const int machine = static_cast<int>(std::thread::hardware_concurrency());
  if (machine <= 0 || requested <= machine) return requested;
  std::cerr << "tuneray: note: --threads " << requested << " clamped to this machine's " << machine
            << " hardware threads\n";
  return machine;
}

void check_image_memory(int width, int height, const std::string& what) {
  const uint64_t available = available_memory_bytes();
  const uint64_t needed =
      static_cast<uint64_t>(width) * static_cast<uint64_t>(height) * Film::kBytesPerPixelBound;
  if (available == 0 || needed <= available) return;
  std::ostringstream message;
  message << what << " " << width << "x" << height << " needs about " << (needed >> 20)
          << " MiB, more than the " << (available >> 20) << " MiB this machine has available";
  throw std::invalid_argument(message.str());
}

}  // namespace tuneray
