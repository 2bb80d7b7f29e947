// Creates a backend by name from a `key=value,...` parameter string (the CLI's --bvh).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "accel/accel.h"

namespace tuneray {

// Splits "a=1,b=high" into {a: "1", b: "high"}. Throws std::invalid_argument on a malformed
// item or a repeated key.
std::map<std::string, std::string> parse_key_values(const std::string& text);

std::vector<std::string> accel_backend_names();

// Throws std::invalid_argument naming the bad backend/parameter and listing the valid ones.
std::unique_ptr<Accel> make_accel(const std::string& backend, const std::string& params = "");

}  // namespace tuneray
