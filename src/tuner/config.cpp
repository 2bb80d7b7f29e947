#include "tuner/config.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace tuneray::tuner {

size_t ParamSpec::cardinality() const {
  switch (kind) {
    case ParamKind::kInt:
      return static_cast<size_t>(hi - lo) + 1;
    case ParamKind::kIntSet:
      return int_values.size();
    case ParamKind::kEnum:
      return labels.size();
    case ParamKind::kBool:
      return 2;
    case ParamKind::kReal:
      return 0;
  }
  return 0;
}

Config::Config(std::shared_ptr<const ParamList> params, std::vector<double> values)
    : params_(std::move(params)), values_(std::move(values)) {
  if (!params_ || params_->size() != values_.size()) {
    throw std::invalid_argument("Config: value count does not match the space");
  }
}

size_t Config::index_of(std::string_view name) const {
  if (params_) {
    for (size_t i = 0; i < params_->size(); ++i) {
      if ((*params_)[i].name == name) return i;
    }
  }
  throw std::invalid_argument("Config: unknown parameter '" + std::string(name) + "'");
}

namespace {
[[noreturn]] void wrong_kind(const ParamSpec& p, const char* wanted) {
  throw std::invalid_argument("Config: parameter '" + p.name + "' is not " + wanted);
}
}  // namespace

int64_t Config::get_int(std::string_view name) const {
  const size_t i = index_of(name);
  const auto kind = (*params_)[i].kind;
  if (kind != ParamKind::kInt && kind != ParamKind::kIntSet) wrong_kind((*params_)[i], "an int");
  return static_cast<int64_t>(values_[i]);
}

double Config::get_real(std::string_view name) const {
  const size_t i = index_of(name);
  const auto kind = (*params_)[i].kind;
  if (kind == ParamKind::kEnum || kind == ParamKind::kBool) wrong_kind((*params_)[i], "numeric");
  return values_[i];
}

const std::string& Config::get_enum(std::string_view name) const {
  const size_t i = index_of(name);
  if ((*params_)[i].kind != ParamKind::kEnum) wrong_kind((*params_)[i], "an enum");
  return (*params_)[i].labels[static_cast<size_t>(values_[i])];
}

bool Config::get_bool(std::string_view name) const {
  const size_t i = index_of(name);
  if ((*params_)[i].kind != ParamKind::kBool) wrong_kind((*params_)[i], "a bool");
  return values_[i] != 0.0;
}

Config& Config::set_int(std::string_view name, int64_t value) {
  const size_t i = index_of(name);
  const ParamSpec& p = (*params_)[i];
  const bool in_range = p.kind == ParamKind::kInt && value >= p.lo && value <= p.hi;
  const bool in_set =
      p.kind == ParamKind::kIntSet &&
      std::find(p.int_values.begin(), p.int_values.end(), value) != p.int_values.end();
  if (!in_range && !in_set) {
    throw std::invalid_argument("Config: " + std::to_string(value) + " is not a value of '" +
                                p.name + "'");
  }
  values_[i] = static_cast<double>(value);
  return *this;
}

Config& Config::set_real(std::string_view name, double value) {
  const size_t i = index_of(name);
  const ParamSpec& p = (*params_)[i];
  if (p.kind != ParamKind::kReal) wrong_kind(p, "a real");
  if (!(value >= p.lo && value <= p.hi)) {
    throw std::invalid_argument("Config: value out of range for '" + p.name + "'");
  }
  values_[i] = value;
  return *this;
}

Config& Config::set_enum(std::string_view name, std::string_view label) {
  const size_t i = index_of(name);
  const ParamSpec& p = (*params_)[i];
  if (p.kind != ParamKind::kEnum) wrong_kind(p, "an enum");
  const auto it = std::find(p.labels.begin(), p.labels.end(), label);
  if (it == p.labels.end()) {
    throw std::invalid_argument("Config: '" + std::string(label) + "' is not a label of '" +
                                p.name + "'");
  }
  values_[i] = static_cast<double>(it - p.labels.begin());
  return *this;
}

Config& Config::set_bool(std::string_view name, bool value) {
  const size_t i = index_of(name);
  if ((*params_)[i].kind != ParamKind::kBool) wrong_kind((*params_)[i], "a bool");
  values_[i] = value ? 1.0 : 0.0;
  return *this;
}

std::string Config::to_string() const {
  std::string text;
  for (size_t i = 0; i < values_.size(); ++i) {
    const ParamSpec& p = (*params_)[i];
    if (i > 0) text += ',';
    text += p.name;
    text += '=';
    switch (p.kind) {
      case ParamKind::kInt:
      case ParamKind::kIntSet:
        text += std::to_string(static_cast<int64_t>(values_[i]));
        break;
      case ParamKind::kReal: {
        char buffer[64];
        const auto result = std::to_chars(buffer, buffer + sizeof buffer, values_[i]);
        text.append(buffer, result.ptr);
        break;
      }
      case ParamKind::kEnum:
        text += p.labels[static_cast<size_t>(values_[i])];
        break;
      case ParamKind::kBool:
        text += values_[i] != 0.0 ? "true" : "false";
        break;
    }
  }
  return text;
}

size_t Config::hash() const {
  size_t h = 0xcbf29ce484222325ULL;
  for (double v : values_) {
    h ^= std::hash<double>{}(v) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
  }
  return h;
}

}  // namespace tuneray::tuner
