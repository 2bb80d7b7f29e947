// Renders a few samples of the built-in Cornell box through the installed tuneray::render, to
// check that its targets, headers and third-party dependencies are complete.
#include <cstdio>

#include "accel/embree_native.h"
#include "render/film.h"
#include "render/sampler.h"
#include "render/tile_renderer.h"
#include "scene/builtins.h"

int main() {
  using namespace tuneray;
  const Scene scene = make_cornell_scene();
  EmbreeNativeAccel accel;
  accel.build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
               scene.triangles.size()});
  RenderSettings settings;
  settings.width = 16;
  settings.height = 16;
  const PcgSampler sampler(settings.seed);  // the renderer keeps a reference to it
  TileRenderer renderer(scene, accel, scene.cameras.at(0), settings, sampler);
  Film film(settings.width, settings.height);
  renderer.render_pass(film, 0, 4);
  const Image image = film.resolve();
  double sum = 0.0;
  for (size_t i = 0; i < image.pixel_count(); ++i) {
    sum += image.data()[i].x + image.data()[i].y + image.data()[i].z;
  }
  // The box is lit: an all-black frame means the renderer did not run.
  std::printf("mean radiance = %.4f\n", sum / (3.0 * static_cast<double>(image.pixel_count())));
}
