// Loads each texture file once, however many materials use it.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "scene/scene.h"

namespace tuneray {

class TextureCache {
 public:
  explicit TextureCache(std::vector<Texture>& textures) : textures_(textures) {}

  // Index into the texture list of the image at `path`, loading it on first use (8-bit files are
  // decoded from sRGB to linear). Throws SceneError naming the texture and `referrer` (the file
  // that asked for it) when it is missing or unreadable.
  int32_t get(const std::string& path, const std::string& referrer);

 private:
  std::vector<Texture>& textures_;
  std::unordered_map<std::string, int32_t> index_of_path_;
};

}  // namespace tuneray
