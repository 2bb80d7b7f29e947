#include "scene/one_texel.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <tuple>

namespace tuneray {

namespace {

int wrap(int i, int n) {
  int r = i % n;
  return r < 0 ? r + n : r;
}

// Texel rows are stored top first; texture y counts from the bottom (see texture_lookup.h).
const Color& texel(const Image& img, int x, int y_from_bottom) {
  return img.at(wrap(x, img.width()), img.height() - 1 - wrap(y_from_bottom, img.height()));
}

std::tuple<uint32_t, uint32_t, uint32_t> colour_key(Color c) {
  uint32_t r, g, b;
  std::memcpy(&r, &c.x, 4);
  std::memcpy(&g, &c.y, 4);
  std::memcpy(&b, &c.z, 4);
  return {r, g, b};
}

}  // namespace

OneTexelStats collapse_one_texel_textures(Scene& scene, bool apply) {
  OneTexelStats stats;
  if (scene.uvs.empty()) return stats;
  std::map<std::tuple<uint32_t, uint32_t, uint32_t, uint32_t>, uint32_t> clones;
  const size_t original_materials = scene.materials.size();
  for (size_t t = 0; t < scene.triangles.size(); ++t) {
    uint32_t mid = scene.material_ids[t];
    if (mid >= original_materials) continue;
    const Material& m = scene.materials[mid];
    if (m.base_texture == kNoTexture) continue;
    const Image& img = scene.textures[static_cast<size_t>(m.base_texture)].image;
    if (img.empty()) continue;
    float u[3], v[3];
    bool finite = true;
    for (int k = 0; k < 3; ++k) {
      Vec2f uv = scene.uvs[scene.triangles[t].v[k]];
      u[k] = uv.x * img.width();
      v[k] = uv.y * img.height();
      finite = finite && std::isfinite(u[k]) && std::isfinite(v[k]) && std::abs(u[k]) < 1e8f &&
               std::abs(v[k]) < 1e8f;
    }
    if (!finite) continue;
    auto same = [](const float* a) {
      return std::floor(a[0]) == std::floor(a[1]) && std::floor(a[0]) == std::floor(a[2]);
    };
    if (!same(u) || !same(v)) continue;
    ++stats.candidates;
    // Bilinear lookups read texels floor(c - 0.5) and the next one, for c over the triangle.
    int x0 = static_cast<int>(std::floor(*std::min_element(u, u + 3) - 0.5f));
    int x1 = static_cast<int>(std::floor(*std::max_element(u, u + 3) - 0.5f)) + 1;
    int y0 = static_cast<int>(std::floor(*std::min_element(v, v + 3) - 0.5f));
    int y1 = static_cast<int>(std::floor(*std::max_element(v, v + 3) - 0.5f)) + 1;
    Color c = texel(img, x0, y0);
    bool constant = true;
    for (int y = y0; y <= y1 && constant; ++y)
      for (int x = x0; x <= x1 && constant; ++x) constant = texel(img, x, y) == c;
    if (!constant) continue;
    ++stats.collapsed;
    if (!apply) continue;
    auto [r, g, b] = colour_key(c);
    auto key = std::make_tuple(mid, r, g, b);
    auto it = clones.find(key);
    if (it == clones.end()) {
      Material clone = scene.materials[mid];
      clone.name += "#texel";
      clone.base_color *= c;
      clone.base_texture = kNoTexture;
      scene.materials.push_back(clone);
      it = clones.emplace(key, static_cast<uint32_t>(scene.materials.size() - 1)).first;
      ++stats.materials_added;
    }
    scene.material_ids[t] = it->second;
  }
  return stats;
}

}  // namespace tuneray
