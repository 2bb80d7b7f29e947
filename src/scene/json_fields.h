// Typed access to a JSON scene with errors that name the file and the key path
// ("scene.json: cameras[1].fov: expected a number").
#pragma once

#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>

#include "math/vec.h"

namespace tuneray {

class JsonFields {
 public:
  JsonFields(const nlohmann::json& value, std::string file, std::string path)
      : value_(value), file_(std::move(file)), path_(std::move(path)) {}

  const nlohmann::json& value() const { return value_; }
  const std::string& path() const { return path_; }

  [[noreturn]] void fail(const std::string& problem) const;

  // Requires an object whose keys are all in `allowed` (typos are errors, not silently ignored).
  void expect_object(std::initializer_list<const char*> allowed) const;
  bool has(const char* key) const { return value_.contains(key); }
  JsonFields child(const char* key) const;
  JsonFields element(size_t index) const;
  size_t array_size() const;  // requires an array

  float number() const;
  std::string string() const;
  bool boolean() const;
  Vec3f vec3() const;   // [x, y, z]
  Vec3f color() const;  // [r, g, b] or one number for grey; components must be >= 0

  // Value of `key` if present, else `fallback`.
  float number_or(const char* key, float fallback) const;
  Vec3f vec3_or(const char* key, Vec3f fallback) const;
  std::string string_or(const char* key, const std::string& fallback) const;

 private:
  const nlohmann::json& value_;
  std::string file_, path_;
};

}  // namespace tuneray
