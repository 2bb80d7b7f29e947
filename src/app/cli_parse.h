// Small parsers for option values shared by several commands (parse_size, in
// render/image_size.h so the bench tools reach it too, comes with this header).
#pragma once

#include <CLI/CLI.hpp>

#include "render/image_size.h"

namespace tuneray {

// Adds to every option of `app` and its subcommands a check that refuses a value reading as
// NaN or infinity ("nan", "inf", "-Infinity", "1e999"): CLI11's range checks let NaN through,
// and a NaN frame budget or clamp would silently give an empty or black image.
void refuse_non_finite_numbers(CLI::App& app);

}  // namespace tuneray
