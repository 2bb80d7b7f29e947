// Small parsers for option values shared by several commands.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <utility>

namespace tuneray {

// "640x360" → {640, 360}; throws std::invalid_argument with the text on anything else.
std::pair<int, int> parse_size(const std::string& text);

// Adds to every option of `app` and its subcommands a check that refuses a value reading as
// NaN or infinity ("nan", "inf", "-Infinity", "1e999"): CLI11's range checks let NaN through,
// and a NaN frame budget or clamp would silently give an empty or black image.
void refuse_non_finite_numbers(CLI::App& app);

}  // namespace tuneray
