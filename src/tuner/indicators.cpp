#include "tuner/indicators.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace tuneray::tuner {

IndicatorSchema& IndicatorSchema::add(std::string name, double lo, double hi) {
  if (!(lo < hi)) throw std::invalid_argument("IndicatorSchema: empty range for " + name);
  for (const auto& e : entries_) {
    if (e.name == name) throw std::invalid_argument("IndicatorSchema: duplicate " + name);
  }
  entries_.push_back({std::move(name), lo, hi});
  return *this;
}

State IndicatorSchema::make(
    std::initializer_list<std::pair<std::string_view, double>> values) const {
  State state(size(), std::nan(""));
  for (const auto& [key, value] : values) {
    // A plain copy for the lambda: clang 14 cannot capture structured bindings.
    const std::string_view name = key;
    const auto it = std::find_if(entries_.begin(), entries_.end(),
                                 [&](const Entry& e) { return e.name == name; });
    if (it == entries_.end()) {
      throw std::invalid_argument("IndicatorSchema: unknown indicator " + std::string(name));
    }
    state[static_cast<size_t>(it - entries_.begin())] = value;
  }
  for (size_t i = 0; i < size(); ++i) {
    if (std::isnan(state[i])) {
      throw std::invalid_argument("IndicatorSchema: missing indicator " + entries_[i].name);
    }
  }
  return state;
}

std::vector<double> IndicatorSchema::normalise(std::span<const double> state) const {
  if (state.size() != size()) {
    throw std::invalid_argument("IndicatorSchema: state has " + std::to_string(state.size()) +
                                " values, schema has " + std::to_string(size()));
  }
  std::vector<double> normalised(size());
  for (size_t i = 0; i < size(); ++i) {
    const double u = (state[i] - entries_[i].lo) / (entries_[i].hi - entries_[i].lo);
    normalised[i] = std::isnan(u) ? 0.0 : std::clamp(u, 0.0, 1.0);
  }
  return normalised;
}

std::string IndicatorSchema::describe() const {
  std::string text;
  char buffer[64];
  for (const auto& e : entries_) {
    text += e.name + "[";
    text.append(buffer, std::to_chars(buffer, buffer + sizeof buffer, e.lo).ptr);
    text += ",";
    text.append(buffer, std::to_chars(buffer, buffer + sizeof buffer, e.hi).ptr);
    text += "];";
  }
  return text;
}

}  // namespace tuneray::tuner
