#include "tuner/space.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace tuneray::tuner {

namespace {

constexpr int kRepairSteps = 20;

double clamp01(double u) {
  return std::isnan(u) ? 0.0 : std::clamp(u, 0.0, 1.0);
}

size_t cell_of(double u, size_t cells) {
  return std::min(cells - 1, static_cast<size_t>(clamp01(u) * static_cast<double>(cells)));
}

double cell_centre(size_t index, size_t cells) {
  return (static_cast<double>(index) + 0.5) / static_cast<double>(cells);
}

// Index of a stored value inside its discrete domain.
size_t discrete_index(const ParamSpec& p, double value) {
  switch (p.kind) {
    case ParamKind::kInt:
      return static_cast<size_t>(value - p.lo);
    case ParamKind::kIntSet:
      return static_cast<size_t>(
          std::find(p.int_values.begin(), p.int_values.end(), static_cast<int64_t>(value)) -
          p.int_values.begin());
    default:
      return static_cast<size_t>(value);
  }
}

double discrete_value(const ParamSpec& p, size_t index) {
  switch (p.kind) {
    case ParamKind::kInt:
      return p.lo + static_cast<double>(index);
    case ParamKind::kIntSet:
      return static_cast<double>(p.int_values[index]);
    default:
      return static_cast<double>(index);
  }
}

std::string format_double(double v) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

}  // namespace

Space::Space() : params_(std::make_shared<ParamList>()), shared_(params_) {}

Space& Space::add(ParamSpec spec) {
  for (const auto& p : *params_) {
    if (p.name == spec.name) throw std::invalid_argument("Space: duplicate parameter " + p.name);
  }
  if (spec.name.empty() || spec.name.find_first_of("=, \t\n") != std::string::npos) {
    throw std::invalid_argument(
        "Space: parameter names must be non-empty without '=', ',' or "
        "spaces: '" +
        spec.name + "'");
  }
  // Copy on write: configurations made earlier keep the parameter list they were made with.
  auto copy = std::make_shared<ParamList>(*params_);
  copy->push_back(std::move(spec));
  params_ = copy;
  shared_ = params_;
  return *this;
}

Space& Space::add_int(std::string name, int64_t lo, int64_t hi, int64_t default_value) {
  if (lo > hi || default_value < lo || default_value > hi) {
    throw std::invalid_argument("Space: bad int range or default for " + name);
  }
  ParamSpec p;
  p.name = std::move(name);
  p.kind = ParamKind::kInt;
  p.lo = static_cast<double>(lo);
  p.hi = static_cast<double>(hi);
  p.default_value = static_cast<double>(default_value);
  return add(std::move(p));
}

Space& Space::add_int_set(std::string name, std::vector<int64_t> values, int64_t default_value) {
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  if (values.empty() || std::find(values.begin(), values.end(), default_value) == values.end()) {
    throw std::invalid_argument("Space: empty value set or default not in set for " + name);
  }
  ParamSpec p;
  p.name = std::move(name);
  p.kind = ParamKind::kIntSet;
  p.int_values = std::move(values);
  p.default_value = static_cast<double>(default_value);
  return add(std::move(p));
}

Space& Space::add_real(std::string name, double lo, double hi, double default_value, Scale scale) {
  if (!(lo < hi) || !(default_value >= lo && default_value <= hi) ||
      (scale == Scale::kLog && !(lo > 0.0))) {
    throw std::invalid_argument("Space: bad real range or default for " + name);
  }
  ParamSpec p;
  p.name = std::move(name);
  p.kind = ParamKind::kReal;
  p.lo = lo;
  p.hi = hi;
  p.log_scale = scale == Scale::kLog;
  p.default_value = default_value;
  return add(std::move(p));
}

Space& Space::add_enum(std::string name, std::vector<std::string> labels,
                       std::string_view default_label) {
  const auto it = std::find(labels.begin(), labels.end(), default_label);
  if (it == labels.end()) throw std::invalid_argument("Space: default not a label of " + name);
  for (const auto& label : labels) {
    if (label.empty() || label.find_first_of("=, \t\n") != std::string::npos) {
      throw std::invalid_argument("Space: bad enum label '" + label + "'");
    }
  }
  ParamSpec p;
  p.name = std::move(name);
  p.kind = ParamKind::kEnum;
  p.default_value = static_cast<double>(it - labels.begin());
  p.labels = std::move(labels);
  return add(std::move(p));
}

Space& Space::add_bool(std::string name, bool default_value) {
  ParamSpec p;
  p.name = std::move(name);
  p.kind = ParamKind::kBool;
  p.default_value = default_value ? 1.0 : 0.0;
  return add(std::move(p));
}

Space& Space::add_constraint(std::string description, Predicate constraint) {
  constraints_.emplace_back(std::move(description), std::move(constraint));
  return *this;
}

Space& Space::add_condition(std::string_view name, Predicate active) {
  const size_t i = index_of(name);
  auto copy = std::make_shared<ParamList>(*params_);
  (*copy)[i].active_when = std::move(active);
  params_ = copy;
  shared_ = params_;
  return *this;
}

Space::Predicate Space::when_enum_not(std::string name, std::vector<std::string> labels) {
  return [name = std::move(name), labels = std::move(labels)](const Config& c) {
    const std::string& label = c.get_enum(name);
    return std::find(labels.begin(), labels.end(), label) == labels.end();
  };
}

size_t Space::index_of(std::string_view name) const {
  for (size_t i = 0; i < params_->size(); ++i) {
    if ((*params_)[i].name == name) return i;
  }
  throw std::invalid_argument("Space: unknown parameter '" + std::string(name) + "'");
}

Config Space::default_config() const {
  std::vector<double> values;
  values.reserve(size());
  for (const auto& p : *params_) values.push_back(p.default_value);
  return Config(shared_, std::move(values));
}

Config Space::canonical(const Config& config) const {
  Config result = config;
  std::vector<double> values = config.values();
  bool changed = false;
  for (size_t i = 0; i < size(); ++i) {
    const ParamSpec& p = (*params_)[i];
    if (p.active_when && !p.active_when(result) && values[i] != p.default_value) {
      values[i] = p.default_value;
      result = Config(shared_, values);
      changed = true;
    }
  }
  return changed ? result : config;
}

bool Space::is_active(const Config& config, size_t index) const {
  const ParamSpec& p = (*params_).at(index);
  return !p.active_when || p.active_when(config);
}

Config Space::decode(std::span<const double> point) const {
  if (point.size() != size()) throw std::invalid_argument("Space::decode: wrong dimension");
  std::vector<double> values(size());
  for (size_t i = 0; i < size(); ++i) {
    const ParamSpec& p = (*params_)[i];
    const double u = clamp01(point[i]);
    if (p.kind == ParamKind::kReal) {
      values[i] = p.log_scale ? std::exp(std::log(p.lo) + u * (std::log(p.hi) - std::log(p.lo)))
                              : p.lo + u * (p.hi - p.lo);
      values[i] = std::clamp(values[i], p.lo, p.hi);
    } else {
      values[i] = discrete_value(p, cell_of(u, p.cardinality()));
    }
  }
  return canonical(Config(shared_, std::move(values)));
}

std::vector<double> Space::encode(const Config& config) const {
  if (config.size() != size()) throw std::invalid_argument("Space::encode: wrong dimension");
  std::vector<double> point(size());
  for (size_t i = 0; i < size(); ++i) {
    const ParamSpec& p = (*params_)[i];
    const double v = config.values()[i];
    if (p.kind == ParamKind::kReal) {
      point[i] = p.log_scale ? (std::log(v) - std::log(p.lo)) / (std::log(p.hi) - std::log(p.lo))
                             : (v - p.lo) / (p.hi - p.lo);
      point[i] = clamp01(point[i]);
    } else {
      point[i] = cell_centre(discrete_index(p, v), p.cardinality());
    }
  }
  return point;
}

bool Space::satisfies_constraints(const Config& config) const {
  for (const auto& [description, constraint] : constraints_) {
    if (!constraint(config)) return false;
  }
  return true;
}

Config Space::feasible(std::vector<double>& point) const {
  for (double& u : point) u = clamp01(u);
  Config config = decode(point);
  if (satisfies_constraints(config)) return config;
  const std::vector<double> origin = encode(default_config());
  std::vector<double> candidate(point.size());
  for (int step = kRepairSteps - 1; step >= 0; --step) {
    const double t = static_cast<double>(step) / kRepairSteps;
    for (size_t i = 0; i < point.size(); ++i) {
      candidate[i] = origin[i] + t * (point[i] - origin[i]);
    }
    config = decode(candidate);
    if (satisfies_constraints(config)) {
      point = candidate;
      return config;
    }
  }
  throw std::logic_error("Space: the default configuration violates a constraint");
}

Config Space::parse(std::string_view text) const {
  Config config = default_config();
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find(',', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view item = text.substr(start, end - start);
    start = end + 1;
    if (item.empty()) continue;
    const size_t eq = item.find('=');
    if (eq == std::string_view::npos) {
      throw std::invalid_argument("Space::parse: expected name=value, got '" + std::string(item) +
                                  "'");
    }
    const std::string_view name = item.substr(0, eq);
    const std::string value(item.substr(eq + 1));
    const ParamSpec& p = param(index_of(name));
    char* parse_end = nullptr;
    switch (p.kind) {
      case ParamKind::kInt:
      case ParamKind::kIntSet: {
        const long long v = std::strtoll(value.c_str(), &parse_end, 10);
        if (value.empty() || *parse_end != '\0') {
          throw std::invalid_argument("Space::parse: bad integer for " + p.name);
        }
        config.set_int(name, v);
        break;
      }
      case ParamKind::kReal: {
        const double v = std::strtod(value.c_str(), &parse_end);
        if (value.empty() || *parse_end != '\0') {
          throw std::invalid_argument("Space::parse: bad real for " + p.name);
        }
        config.set_real(name, v);
        break;
      }
      case ParamKind::kEnum:
        config.set_enum(name, value);
        break;
      case ParamKind::kBool:
        if (value != "true" && value != "false") {
          throw std::invalid_argument("Space::parse: bool " + p.name + " must be true or false");
        }
        config.set_bool(name, value == "true");
        break;
    }
  }
  return canonical(config);
}

std::string Space::describe() const {
  std::string text;
  for (const auto& p : *params_) {
    text += p.name;
    switch (p.kind) {
      case ParamKind::kInt:
        text += ":int[";
        text += format_double(p.lo);
        text += ',';
        text += format_double(p.hi);
        text += ']';
        break;
      case ParamKind::kIntSet:
        text += ":set{";
        for (size_t i = 0; i < p.int_values.size(); ++i) {
          if (i > 0) text += ',';
          text += std::to_string(p.int_values[i]);
        }
        text += "}";
        break;
      case ParamKind::kReal:
        text += p.log_scale ? ":log[" : ":real[";
        text += format_double(p.lo);
        text += ',';
        text += format_double(p.hi);
        text += ']';
        break;
      case ParamKind::kEnum:
        text += ":enum{";
        for (size_t i = 0; i < p.labels.size(); ++i) {
          if (i > 0) text += ',';
          text += p.labels[i];
        }
        text += "}";
        break;
      case ParamKind::kBool:
        text += ":bool";
        break;
    }
    text += '=';
    text += format_double(p.default_value);
    if (p.active_when) text += "?";
    text += ";";
  }
  return text;
}

}  // namespace tuneray::tuner
