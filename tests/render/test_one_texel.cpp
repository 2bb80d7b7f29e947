// One-texel texture folding: triangles inside one texel of a uniform neighbourhood get a
// constant material and render exactly as before; others keep the texture.
#include <gtest/gtest.h>

#include "accel/embree_native.h"
#include "render/film.h"
#include "render/tile_renderer.h"
#include "scene/load.h"
#include "scene/one_texel.h"

namespace tuneray {
namespace {

// The Cornell box with a 4x4 texture on every material: texels (0..2, 0..2) (bottom-left
// corner) are one colour, the rest a checkerboard. UVs of each triangle: all in texel
// `texel` (texel units), spanning a tenth of it.
Scene textured_cornell(float texel_u, float texel_v) {
  Scene scene = load_scene("cornell");
  Texture t;
  t.image = Image(4, 4);
  for (int row = 0; row < 4; ++row)
    for (int x = 0; x < 4; ++x) {
      int from_bottom = 3 - row;
      bool quadrant = x < 3 && from_bottom < 3;
      t.image.at(x, row) =
          quadrant ? Color(0.2f, 0.5f, 0.9f) : ((x + from_bottom) % 2 ? Color(1.0f) : Color(0.1f));
    }
  scene.textures.push_back(t);
  for (Material& m : scene.materials) m.base_texture = 0;
  scene.uvs.assign(scene.positions.size(), Vec2f{0, 0});
  for (const Triangle& tri : scene.triangles)
    for (int k = 0; k < 3; ++k)
      scene.uvs[tri.v[k]] = {(texel_u + 0.45f + 0.05f * k) / 4, (texel_v + 0.5f) / 4};
  return scene;
}

Image render(const Scene& scene) {
  EmbreeNativeAccel accel;
  accel.build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
               scene.triangles.size()});
  RenderSettings s;
  s.width = 32;
  s.height = 24;
  s.seed = 9;
  PcgSampler sampler(s.seed);
  TileRenderer renderer(scene, accel, scene.cameras.at(0), s, sampler);
  Film film(s.width, s.height);
  renderer.render_pass(film, 0, 2);
  return film.resolve();
}

TEST(OneTexel, UniformNeighbourhoodIsFoldedAndRendersTheSame) {
  Scene scene = textured_cornell(0.0f, 0.0f);  // texel (0,0) but bilinear reads wrap to 3
  Scene inner = textured_cornell(1.0f, 1.0f);  // inside the uniform 3x3 corner
  OneTexelStats edge = collapse_one_texel_textures(scene, false);
  EXPECT_EQ(edge.candidates, scene.triangles.size());
  EXPECT_EQ(edge.collapsed, 0u) << "bilinear footprint reaches the checkerboard";

  Image before = render(inner);
  Scene folded = inner;
  OneTexelStats stats = collapse_one_texel_textures(folded);
  EXPECT_EQ(stats.collapsed, folded.triangles.size());
  for (uint32_t id : folded.material_ids) EXPECT_EQ(folded.materials[id].base_texture, kNoTexture);
  Image after = render(folded);
  for (int y = 0; y < before.height(); ++y)
    for (int x = 0; x < before.width(); ++x)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(after.at(x, y)[c], before.at(x, y)[c], 1e-5f * (1 + before.at(x, y)[c]));
}

TEST(OneTexel, TrianglesSpanningTexelsAreKept) {
  Scene scene = textured_cornell(1.0f, 1.0f);
  for (const Triangle& tri : scene.triangles) scene.uvs[tri.v[2]] = {0.9f, 0.9f};
  OneTexelStats stats = collapse_one_texel_textures(scene);
  EXPECT_EQ(stats.candidates, 0u);
  EXPECT_EQ(stats.materials_added, 0u);
}

}  // namespace
}  // namespace tuneray
