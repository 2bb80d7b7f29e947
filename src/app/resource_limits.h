// Limits the command line enforces before any work starts: numbers that are not finite, more
// threads than the machine has, images that do not fit in memory.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

namespace tuneray {

// Adds to every option of `app` and its subcommands a check that refuses a value reading as
// NaN or infinity ("nan", "inf", "-Infinity", "1e999"): CLI11's range checks let NaN through,
// and a NaN frame budget or clamp would silently produce an empty or black image.
void refuse_non_finite_numbers(CLI::App& app);

// `requested` threads (0 = all cores) clamped to the machine's hardware threads; a note on
// stderr when clamped.
int clamp_threads(int requested);

// Throws std::invalid_argument with both figures when a width x height render would need more
// memory than the machine has available (MemAvailable in /proc/meminfo; no check where that
// cannot be read).
void check_image_memory(int width, int height, const std::string& what);

}  // namespace tuneray
