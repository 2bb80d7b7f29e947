#include "scene/texture_cache.h"

#include <filesystem>

#include "image/io.h"
#include "image/texel_check.h"
#include "scene/load.h"

namespace tuneray {

int32_t TextureCache::get(const std::string& path, const std::string& referrer) {
  namespace fs = std::filesystem;
  std::error_code ec;
  std::string key = fs::weakly_canonical(fs::path(path), ec).string();
  if (ec) key = fs::path(path).lexically_normal().string();
  auto found = index_of_path_.find(key);
  if (found != index_of_path_.end()) return found->second;

  if (!fs::is_regular_file(path)) throw SceneError(referrer + ": texture '" + path + "' not found");
  Texture texture;
  texture.path = path;
  try {
    texture.image = read_image(path);
  } catch (const std::exception& e) {
    throw SceneError(referrer + ": cannot read texture '" + path + "': " + e.what());
  }
  if (texture.image.empty()) throw SceneError(referrer + ": texture '" + path + "' is empty");
  if (auto bad = find_bad_texel(texture.image))
    throw SceneError(referrer + ": texture '" + path + "': " + describe_bad_texel(*bad));
  auto index = static_cast<int32_t>(textures_.size());
  textures_.push_back(std::move(texture));
  index_of_path_.emplace(key, index);
  return index;
}

}  // namespace tuneray
