#include "app/cli_parse.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace tuneray {

std::pair<int, int> parse_size(const std::string& text) {
  size_t x = text.find_first_of("xX");
  auto bad = [&] {
    return std::invalid_argument("bad --size '" + text +
                                 "': expected WIDTHxHEIGHT, each 1..16384, e.g. 640x360");
  };
  if (x == std::string::npos) throw bad();
  int w = 0, h = 0;
  auto r1 = std::from_chars(text.data(), text.data() + x, w);
  auto r2 = std::from_chars(text.data() + x + 1, text.data() + text.size(), h);
  if (r1.ec != std::errc() || r1.ptr != text.data() + x || r2.ec != std::errc() ||
      r2.ptr != text.data() + text.size() || w < 1 || h < 1 || w > 16384 || h > 16384)
    throw bad();
  return {w, h};
}

namespace {

bool reads_as_non_finite(const std::string& text) {
  if (text.empty()) return false;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && !std::isfinite(v);
}

void add_check_to_every_option(CLI::App& app, const CLI::Validator& check) {
  for (CLI::Option* option : app.get_options())
    if (option->get_expected_min() > 0) option->check(check);
  for (CLI::App* sub : app.get_subcommands({})) add_check_to_every_option(*sub, check);
}

}  // namespace

void refuse_non_finite_numbers(CLI::App& app) {
  add_check_to_every_option(app, CLI::Validator(
                                     [](std::string& value) {
                                       return reads_as_non_finite(value)
                                                  ? "'" + value + "' is not a finite number"
                                                  : std::string();
                                     },
                                     ""));
}

}  // namespace tuneray
