#include "app/cli_parse.h"

#include <cmath>
#include <cstdlib>

namespace tuneray {

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
