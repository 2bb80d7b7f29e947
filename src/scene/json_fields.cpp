#include "scene/json_fields.h"

#include <cmath>

#include "scene/load.h"

namespace tuneray {

void JsonFields::fail(const std::string& problem) const {
  throw SceneError(file_ + ": " + (path_.empty() ? "top level" : path_) + ": " + problem);
}

void JsonFields::expect_object(std::initializer_list<const char*> allowed) const {
  if (!value_.is_object()) fail("expected an object");
  for (const auto& item : value_.items()) {
    bool known = false;
    for (const char* key : allowed) known |= item.key() == key;
    if (known) continue;
    std::string list;
    for (const char* key : allowed) list += (list.empty() ? "" : ", ") + std::string(key);
    JsonFields(item.value(), file_, path_.empty() ? item.key() : path_ + "." + item.key())
        .fail("unknown key (expected one of: " + list + ")");
  }
}

JsonFields JsonFields::child(const char* key) const {
  if (!value_.contains(key)) fail(std::string("missing key '") + key + "'");
  return {value_.at(key), file_, path_.empty() ? key : path_ + "." + key};
}

JsonFields JsonFields::element(size_t index) const {
  return {value_.at(index), file_, path_ + "[" + std::to_string(index) + "]"};
}

size_t JsonFields::array_size() const {
  if (!value_.is_array()) fail("expected an array");
  return value_.size();
}

float JsonFields::number() const {
  if (!value_.is_number()) fail("expected a number");
  auto v = value_.get<double>();
  if (!std::isfinite(v)) fail("expected a finite number");
  return static_cast<float>(v);
}

std::string JsonFields::string() const {
  if (!value_.is_string()) fail("expected a string");
  return value_.get<std::string>();
}

bool JsonFields::boolean() const {
  if (!value_.is_boolean()) fail("expected true or false");
  return value_.get<bool>();
}

Vec3f JsonFields::vec3() const {
  if (!value_.is_array() || value_.size() != 3) fail("expected an array of 3 numbers");
  return {element(0).number(), element(1).number(), element(2).number()};
}

Vec3f JsonFields::color() const {
  Vec3f c = value_.is_number() ? Vec3f(number()) : vec3();
  if (min_component(c) < 0) fail("colour components must not be negative");
  return c;
}

float JsonFields::number_or(const char* key, float fallback) const {
  return has(key) ? child(key).number() : fallback;
}

Vec3f JsonFields::vec3_or(const char* key, Vec3f fallback) const {
  return has(key) ? child(key).vec3() : fallback;
}

std::string JsonFields::string_or(const char* key, const std::string& fallback) const {
  return has(key) ? child(key).string() : fallback;
}

}  // namespace tuneray
