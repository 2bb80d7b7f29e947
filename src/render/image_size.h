// The text form of an image size, shared by the command line and the bench tools.
#pragma once

#include <string>
#include <utility>

namespace tuneray {

// "640x360" → {640, 360}; throws std::invalid_argument with the text on anything else.
std::pair<int, int> parse_size(const std::string& text);

}  // namespace tuneray
