#include "bench/render_bench.h"

#include <memory>
#include <stdexcept>

#include "accel/factory.h"
#include "bench/embree_peer.h"
#include "bench/scene_paths.h"
#include "render/film.h"
#include "render/tile_renderer.h"
#include "scene/load.h"
#include "tuning/stats.h"

namespace tuneray {

std::vector<std::string> render_bench_scenes(const RenderBenchOptions& options) {
  if (!options.scenes.empty()) return options.scenes;
  std::vector<std::string> scenes = {"cornell"};
  if (!find_shared_scenes_dir(options.scenes_dir).empty())
    for (const std::string& f : shared_scene_json_files()) scenes.push_back(f);
  return scenes;
}

RenderSpeed measure_render_speed(const std::string& name, const Scene& scene,
                                 const RenderBenchOptions& a, int spp) {
  std::unique_ptr<Accel> accel = make_accel(a.accel, a.bvh);
  BuildStats build = accel->build({scene.positions.data(), scene.positions.size(),
                                   scene.triangles.data(), scene.triangles.size()});
  RenderSettings settings;
  settings.width = a.width;
  settings.height = a.height;
  settings.max_bounces = a.max_bounces;
  PcgSampler sampler(1);
  TileRenderer renderer(scene, *accel, scene.cameras.at(0), settings, sampler);
  Film film(a.width, a.height);
  renderer.render_pass(film, 0, 1);  // warm-up: caches, page faults, TBB threads
  std::vector<double> ms, mrays;
  for (int r = 0; r < a.repeats; ++r) {
    PassStats p = renderer.render_pass(film, 1 + r * spp, spp);
    ms.push_back(p.render_ms / spp);
    mrays.push_back(p.mrays_per_s());
  }
  RenderSpeed r;
  r.scene = name;
  r.accel = accel->name() + " " + accel->describe();
  r.triangles = scene.triangles.size();
  r.build_ms = build.build_ms;
  r.ms_per_spp = median(ms);
  r.mrays = median(mrays);
  return r;
}

EmbreeComparison compare_with_embree(const RenderBenchOptions& a) {
  EmbreeComparison c;
  EmbreePeer peer;
  peer.width = a.width;
  peer.height = a.height;
  peer.max_path_length = a.max_bounces;
  c.error = embree_peer_missing(peer);
  if (!c.error.empty()) return c;
  EmbreePeerTiming embree;
  try {
    embree = embree_peer_benchmark(peer, c.spp, a.repeats);
  } catch (const std::runtime_error& e) {
    c.error = e.what();
    return c;
  }
  RenderSpeed ours = measure_render_speed("embree-cornell", embree_cornell_scene(peer), a, c.spp);
  c.ok = true;
  c.our_accel = ours.accel;
  c.our_frame_ms = ours.ms_per_spp * c.spp;
  c.embree_frame_ms = embree.frame_ms;
  c.our_mrays = ours.mrays;
  c.embree_mrays = embree.mrays;
  return c;
}

}  // namespace tuneray
