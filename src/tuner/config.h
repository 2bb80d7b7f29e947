// A configuration: one value per parameter of a Space, with named access, a text form and
// value semantics (equality and hashing compare every value exactly).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "tuner/param_spec.h"

namespace tuneray::tuner {

using ParamList = std::vector<ParamSpec>;

class Config {
 public:
  Config() = default;
  // `values` holds the stored form of each parameter (see ParamSpec::default_value).
  Config(std::shared_ptr<const ParamList> params, std::vector<double> values);

  // Named getters throw std::invalid_argument for an unknown name or the wrong kind.
  int64_t get_int(std::string_view name) const;  // kInt and kIntSet
  double get_real(std::string_view name) const;  // kReal (also accepts integer kinds)
  const std::string& get_enum(std::string_view name) const;
  bool get_bool(std::string_view name) const;

  // Setters keep the value inside its domain or throw std::invalid_argument. They do not apply
  // conditions or constraints: pass the result through Space::canonical() for that.
  Config& set_int(std::string_view name, int64_t value);
  Config& set_real(std::string_view name, double value);
  Config& set_enum(std::string_view name, std::string_view label);
  Config& set_bool(std::string_view name, bool value);

  // "name=value,name=value" in parameter order; reals use the shortest exact decimal form so
  // that Space::parse(c.to_string()) == c.
  std::string to_string() const;

  bool empty() const { return values_.empty(); }
  size_t size() const { return values_.size(); }
  const std::vector<double>& values() const { return values_; }
  const ParamList& params() const { return *params_; }
  const std::shared_ptr<const ParamList>& shared_params() const { return params_; }

  bool operator==(const Config& other) const { return values_ == other.values_; }
  size_t hash() const;

 private:
  size_t index_of(std::string_view name) const;
  std::shared_ptr<const ParamList> params_;
  std::vector<double> values_;
};

struct ConfigHash {
  size_t operator()(const Config& c) const { return c.hash(); }
};

}  // namespace tuneray::tuner

template <>
struct std::hash<tuneray::tuner::Config> {
  size_t operator()(const tuneray::tuner::Config& c) const { return c.hash(); }
};
