// Description of one tunable parameter. Shared by Space (which builds them) and Config (which
// reads them to give named access).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace tuneray::tuner {

class Config;

enum class ParamKind {
  kInt,     // integer range [lo, hi]
  kIntSet,  // integer from an explicit value set, e.g. {2, 4, 8}
  kReal,    // real range [lo, hi], linear or log-scaled
  kEnum,    // one label out of a list
  kBool,
};

struct ParamSpec {
  std::string name;
  ParamKind kind = ParamKind::kInt;
  double lo = 0.0;  // kInt, kReal
  double hi = 0.0;
  bool log_scale = false;           // kReal only
  std::vector<int64_t> int_values;  // kIntSet
  std::vector<std::string> labels;  // kEnum
  double default_value = 0.0;       // stored form: value, set member, label index or 0/1
  // When set and false for a configuration, the parameter is ignored by the application and
  // pinned to its default, so configurations differing only in it compare equal.
  std::function<bool(const Config&)> active_when;

  // Number of distinct values of a discrete parameter; 0 for kReal.
  size_t cardinality() const;
};

}  // namespace tuneray::tuner
