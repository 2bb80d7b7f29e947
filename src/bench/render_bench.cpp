#include "bench/render_bench.h"

#include <algorithm>
#include <stdexcept>

#include "accel/factory.h"
#include "bench/embree_peer.h"
#include "bench/scene_paths.h"
#include "scene/load.h"
#include "tuning/interleaved_ratios.h"
#include "tuning/stats.h"

namespace tuneray {

std::vector<std::string> render_bench_scenes(const RenderBenchOptions& options) {
  if (!options.scenes.empty()) return options.scenes;
  std::vector<std::string> scenes = {"cornell"};
  if (!find_shared_scenes_dir(options.scenes_dir).empty())
    for (const std::string& f : shared_scene_json_files()) scenes.push_back(f);
  return scenes;
}

TimedRenderer::TimedRenderer(const Scene& scene, const RenderBenchOptions& a)
    : accel_(make_accel(a.accel, a.bvh)),
      build_(accel_->build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
                            scene.triangles.size()})),
      sampler_(1),
      film_(a.width, a.height) {
  RenderSettings settings;
  settings.width = a.width;
  settings.height = a.height;
  settings.max_bounces = a.max_bounces;
  renderer_ =
      std::make_unique<TileRenderer>(scene, *accel_, scene.cameras.at(0), settings, sampler_);
  pass(1);  // warm-up: caches, page faults, TBB threads
}

PassStats TimedRenderer::pass(int spp) {
  PassStats p = renderer_->render_pass(film_, next_sample_, spp);
  next_sample_ += static_cast<uint32_t>(spp);
  return p;
}

std::string TimedRenderer::accel_description() const {
  return accel_->name() + " " + accel_->describe();
}

RenderSpeed measure_render_speed(const std::string& name, const Scene& scene,
                                 const RenderBenchOptions& a, int spp) {
  TimedRenderer renderer(scene, a);
  std::vector<double> ms, mrays;
  for (int r = 0; r < a.repeats; ++r) {
    PassStats p = renderer.pass(spp);
    ms.push_back(p.render_ms / spp);
    mrays.push_back(p.mrays_per_s());
  }
  RenderSpeed r;
  r.scene = name;
  r.accel = renderer.accel_description();
  r.triangles = scene.triangles.size();
  r.build_ms = renderer.build_ms();
  r.ms_per_spp = median(ms);
  r.mrays = median(mrays);
  return r;
}

std::vector<double> EmbreeComparison::speed_ratios() const {
  std::vector<double> ratios;
  for (size_t r = 0; r < std::min(our_frame_ms.size(), embree_frame_ms.size()); ++r)
    ratios.push_back(embree_frame_ms[r] / our_frame_ms[r]);
  return ratios;
}

double EmbreeComparison::speed_ratio() const {
  // The estimator eval's and tune's comparisons use (of the logarithms, so an even count's
  // median inverts exactly with the pair).
  InterleavedResult rounds;
  rounds.costs = {embree_frame_ms, our_frame_ms};
  return paired_ratio(rounds, 0, 1, RatioEstimator::kMedian).ratio;
}

EmbreeComparison compare_with_embree(const RenderBenchOptions& a) {
  EmbreeComparison c;
  EmbreePeer peer;
  peer.width = a.width;
  peer.height = a.height;
  peer.max_path_length = a.max_bounces;
  c.error = embree_peer_missing(peer);
  if (!c.error.empty()) return c;
  const Scene scene = load_scene(peer.scene);
  TimedRenderer ours(scene, a);
  std::vector<double> our_mrays, embree_mrays;
  for (int r = 0; r < a.repeats; ++r) {
    EmbreePeerTiming embree;
    try {
      embree = embree_peer_benchmark(peer, c.spp, 1);
    } catch (const std::runtime_error& e) {
      c.error = e.what();
      return c;
    }
    c.embree_frame_ms.push_back(embree.frame_ms);
    embree_mrays.push_back(embree.mrays);
    PassStats p = ours.pass(c.spp);
    c.our_frame_ms.push_back(p.render_ms);
    our_mrays.push_back(p.mrays_per_s());
  }
  c.ok = true;
  c.our_accel = ours.accel_description();
  c.our_mrays = median(our_mrays);
  c.embree_mrays = median(embree_mrays);
  return c;
}

}  // namespace tuneray
