// The search space: typed parameters, constraints between them and conditions that switch a
// parameter off.
//
// Every search works in the normalised space [0,1]^n, one coordinate per parameter:
// - a real range maps linearly (or logarithmically with Scale::kLog) onto [0,1];
// - a discrete parameter with k values (int range, value set, enum, bool) splits [0,1] into k
//   equal cells and takes the value of the cell the coordinate falls in; encoding returns the
//   cell centre. Equal cells give every value the same share of Latin Hypercube strata and of
//   simplex moves. Enums are treated as ordered by declaration order.
// - a parameter whose condition is false is pinned to its default (the application ignores it),
//   so points that differ only in ignored parameters decode to the same Config and the sample
//   already recorded for it is reused instead of re-measured.
// - constraints (e.g. min_leaf <= max_leaf) are repaired by moving the point towards the default
//   configuration along a straight line until it is feasible (see feasible()). The default must
//   satisfy every constraint.
#pragma once

#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "tuner/config.h"

namespace tuneray::tuner {

enum class Scale { kLinear, kLog };

class Space {
 public:
  using Predicate = std::function<bool(const Config&)>;

  Space();

  // Adders throw std::invalid_argument on a duplicate name, an empty domain or a default outside
  // the domain. They return *this for chaining.
  Space& add_int(std::string name, int64_t lo, int64_t hi, int64_t default_value);
  Space& add_int_set(std::string name, std::vector<int64_t> values, int64_t default_value);
  Space& add_real(std::string name, double lo, double hi, double default_value,
                  Scale scale = Scale::kLinear);  // kLog needs lo > 0
  Space& add_enum(std::string name, std::vector<std::string> labels,
                  std::string_view default_label);
  Space& add_bool(std::string name, bool default_value);

  // A configuration is feasible when every constraint returns true.
  Space& add_constraint(std::string description, Predicate constraint);
  // `name` is active only when `active` returns true; otherwise it is pinned to its default.
  // Conditions are evaluated in parameter order on a configuration whose earlier parameters are
  // already pinned, so a condition should only read parameters declared before `name`.
  Space& add_condition(std::string_view name, Predicate active);
  // Declarative helper: true when enum `name` has none of `labels`.
  static Predicate when_enum_not(std::string name, std::vector<std::string> labels);

  size_t size() const { return params_->size(); }
  const ParamSpec& param(size_t i) const { return (*params_)[i]; }
  size_t index_of(std::string_view name) const;  // throws std::invalid_argument

  Config default_config() const;
  // Cell/range decoding of a normalised point, then conditions applied. Coordinates are clamped
  // to [0,1]. Does not repair constraints.
  Config decode(std::span<const double> point) const;
  std::vector<double> encode(const Config& config) const;
  // Applies conditions (pinning inactive parameters to their defaults).
  Config canonical(const Config& config) const;
  // Whether parameter `index` is active in `config` (its condition holds; always for a parameter
  // without one). `config` should be canonical, as decode() and parse() return.
  bool is_active(const Config& config, size_t index) const;
  bool satisfies_constraints(const Config& config) const;
  // Clamps `point` to [0,1]^n and, if its configuration violates a constraint, replaces it by
  // the first feasible point on the segment from it to the default (20 evenly spaced steps; the
  // default itself ends the walk). Returns the feasible configuration.
  Config feasible(std::vector<double>& point) const;

  // Parses "name=value,..." (the output of Config::to_string). Missing parameters take their
  // default; unknown names or bad values throw std::invalid_argument. Applies conditions.
  Config parse(std::string_view text) const;

  // Canonical text of the parameter domains (not of the predicates, which cannot be printed).
  // The database refuses to mix samples of spaces whose descriptions differ.
  std::string describe() const;

  const std::shared_ptr<const ParamList>& shared_params() const { return shared_; }

 private:
  Space& add(ParamSpec spec);
  std::shared_ptr<ParamList> params_;
  std::shared_ptr<const ParamList> shared_;
  std::vector<std::pair<std::string, Predicate>> constraints_;
};

}  // namespace tuneray::tuner
