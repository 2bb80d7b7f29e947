// Indicators: the named numbers that describe the current input (the "state" of the tuner).
//
// Each indicator has a fixed range [lo, hi] fixed by the caller, not learnt from the data, so
// that normalised states and the distances between them do not drift as new inputs arrive.
// Values outside the range are clamped to [0,1] after normalisation.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tuneray::tuner {

// Raw indicator values in schema order.
using State = std::vector<double>;

class IndicatorSchema {
 public:
  struct Entry {
    std::string name;
    double lo;
    double hi;
  };

  // Throws std::invalid_argument on a duplicate name or lo >= hi.
  IndicatorSchema& add(std::string name, double lo, double hi);

  size_t size() const { return entries_.size(); }
  const Entry& entry(size_t i) const { return entries_[i]; }

  // Builds a State from named values; every indicator must be given exactly once.
  State make(std::initializer_list<std::pair<std::string_view, double>> values) const;
  // (value - lo) / (hi - lo), clamped to [0,1]. Throws on a wrong dimension.
  std::vector<double> normalise(std::span<const double> state) const;

  // Canonical text of names and ranges, stored in the database as part of the signature.
  std::string describe() const;

 private:
  std::vector<Entry> entries_;
};

}  // namespace tuneray::tuner
