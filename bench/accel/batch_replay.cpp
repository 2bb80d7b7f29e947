// Replays a wavefront render's ray batches through both backends' batch entry points, phase by
// phase (camera rays, bounce rays, shadow rays), so the kernels the render calls are timed on
// the render's own rays without the shading between them. Batches the render handed over as
// planes (camera and bounce rays) are replayed as planes, through the same entry point: until
// the fortieth session they were replayed as records, where native Embree's camera rays went
// through rtcIntersect1M instead of the rtcIntersectNp a frame uses, which overstated our lead
// on camera rays (bmw-m6: 1.3x in the replay, parity in frames).
//
//   batch_replay SCENE.json [--scenes-dir DIR] [--bvh CONFIG] [--size WxH] [--spp N]
//                [--repeats R] [--pollute KiB] [--single 0|1] [--ab-env VAR=VALUE]
//                [--ab-copies K] [--only camera|bounce|shadow]
//
// The batches are recorded once from a single-threaded render with native Embree (a pass-through
// accelerator keeps a copy of every batch), then traced again and again, one thread, native and
// tuned taking turns per repeat; each phase's time is the thread's CPU time (other jobs on a
// shared machine do not inflate it), the median over repeats. `--pollute` reads that many KiB
// of an unrelated buffer after every batch, as the render's shading evicts part of the tree from
// the caches between batches. `--single 1` adds native Embree called once per ray (Accel's
// default batch loop), the yardstick of `bench traversal`'s ray sets.
//
// `--ab-env VAR=VALUE` adds a second tuned backend, built after setting that environment
// variable, to the same rotation, and prints tuned/second per phase: an A/B of an experimental
// switch that the library reads from the environment, on the same rays in one process. With
// `--ab-copies K` each of the two is built K times (trees at other addresses) and timed as the
// mean over its copies. With a variable nothing reads it is an A/A run, which measures what the
// placement of two identical trees alone does to a replay (2026-11-25 on this machine: 0.95 to
// 1.08 with one copy each, conference and bunny).
//
// `--ray-weight W` adds a second tuned backend of the same configuration with ray_weight=W,
// priced by a ray sample (accel/ray_sample.h) of `--ray-sample N` segments (default 4096) taken
// from a separate render of the same view (`--train-spp K` passes after the timed ones, so other
// random numbers than the replayed rays), and prints tuned/weighted per phase as --ab-env does.
//
// `--native-b PARAMS` replaces the tuned backend by a second native one built with these
// parameters (e.g. `tri_accel=bvh4.triangle4`): Embree against Embree on the same rays.
// `--camera N` records the render from the scene's camera N instead of its first.
// `--path-camera K/N` records it from camera K of the N that `tune --cameras N` places along the
// scene's first camera path (or the automatic path of a scene without one), so a replay can look
// at the very views whose frames `tune` measured: on the bunny, the close views (K = 6, 7 of 10)
// are where native's camera rays win, which the scene's first camera does not show.
#include <tbb/global_control.h>
#include <time.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "accel/embree_native.h"
#include "accel/factory.h"
#include "accel/kernel_isa.h"
#include "accel/ray_planes.h"
#include "accel/ray_sample.h"
#include "accel/tuned_bvh.h"
#include "render/blue_noise_sampler.h"
#include "render/film.h"
#include "render/image_size.h"
#include "render/tile_renderer.h"
#include "scene/camera_spline.h"
#include "scene/load.h"

namespace tuneray {
namespace {

enum Phase { kCamera, kBounce, kShadow, kPhases };
const char* const kPhaseName[kPhases] = {"camera", "bounce", "shadow"};

struct Batch {
  Phase phase;
  std::vector<Ray> rays;
  // The rays as the wavefront handed them over as planes (camera and bounce rays): replayed
  // through intersect_planes, the entry point a frame calls, where native Embree reads the
  // planes directly. Empty for batches that came as records (shadow rays).
  std::array<std::vector<float>, 6> planes;

  bool as_planes() const { return !planes[0].empty(); }
  RayPlanes plane_view() const {
    RayPlanes view;
    for (int a = 0; a < 3; ++a) {
      view.org[static_cast<size_t>(a)] = planes[static_cast<size_t>(a)].data();
      view.dir[static_cast<size_t>(a)] = planes[static_cast<size_t>(3 + a)].data();
    }
    view.size = rays.size();
    return view;
  }
};

// Forwards every call to `inner` and keeps a copy of every batch (single-threaded use only).
class RecordingAccel final : public Accel {
 public:
  explicit RecordingAccel(const Accel& inner) : inner_(inner) {}
  std::string name() const override { return inner_.name(); }
  std::string describe() const override { return inner_.describe(); }
  BuildStats build(const GeometryView&) override { return {}; }
  bool intersect(const Ray& ray, Hit& hit) const override { return inner_.intersect(ray, hit); }
  bool occluded(const Ray& ray) const override { return inner_.occluded(ray); }
  void intersect_batch(std::span<const Ray> rays, std::span<Hit> hits,
                       RayCoherence coherence) const override {
    batches.push_back({coherence == RayCoherence::kCoherent ? kCamera : kBounce,
                       std::vector<Ray>(rays.begin(), rays.end()),
                       {}});
    inner_.intersect_batch(rays, hits, coherence);
  }
  void occluded_batch(std::span<const Ray> rays, std::span<uint8_t> occluded) const override {
    batches.push_back({kShadow, std::vector<Ray>(rays.begin(), rays.end()), {}});
    inner_.occluded_batch(rays, occluded);
  }
  void intersect_planes(const RayPlanes& rays, std::span<Hit> hits,
                        RayCoherence coherence) const override {
    Batch b{
        coherence == RayCoherence::kCoherent ? kCamera : kBounce, std::vector<Ray>(rays.size), {}};
    rays_from_planes(rays, b.rays);
    for (size_t a = 0; a < 3; ++a) {
      b.planes[a].assign(rays.org[a], rays.org[a] + rays.size);
      b.planes[3 + a].assign(rays.dir[a], rays.dir[a] + rays.size);
    }
    batches.push_back(std::move(b));
    inner_.intersect_planes(rays, hits, coherence);
  }
  mutable std::vector<Batch> batches;

 private:
  const Accel& inner_;
};

// Native Embree one ray per call: the batch entry points are Accel's defaults, which loop over
// the single-ray calls (what our kernels are measured against in `bench traversal`).
class SingleRayAccel final : public Accel {
 public:
  explicit SingleRayAccel(const Accel& inner) : inner_(inner) {}
  std::string name() const override { return inner_.name(); }
  std::string describe() const override { return inner_.describe(); }
  BuildStats build(const GeometryView&) override { return {}; }
  bool intersect(const Ray& ray, Hit& hit) const override { return inner_.intersect(ray, hit); }
  bool occluded(const Ray& ray) const override { return inner_.occluded(ray); }

 private:
  const Accel& inner_;
};

double thread_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}
double lowest(const std::vector<double>& v) {
  return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end());
}

struct Replayer {
  const std::vector<Batch>* batches;
  int only = -1;  // replay only this phase (--only), e.g. to count one phase's instructions
  std::vector<char> junk;
  std::vector<Hit> hits;
  std::vector<uint8_t> blocked;
  volatile unsigned sink = 0;

  void pollute() {
    unsigned s = 0;
    for (size_t i = 0; i < junk.size(); i += 64) s += static_cast<unsigned char>(junk[i]);
    sink = sink + s;
  }

  // Seconds per phase of one pass over all batches; also a checksum of the answers.
  std::vector<double> run(const Accel& accel, uint64_t& checksum) {
    std::vector<double> seconds(kPhases, 0.0);
    checksum = 0;
    for (const Batch& b : *batches) {
      if (only >= 0 && b.phase != only) continue;
      if (!junk.empty()) pollute();
      const double t0 = thread_seconds();
      if (b.phase == kShadow) {
        blocked.resize(b.rays.size());
        accel.occluded_batch(b.rays, blocked);
        seconds[b.phase] += thread_seconds() - t0;
        for (uint8_t x : blocked) checksum = checksum * 3 + x;
      } else {
        hits.resize(b.rays.size());
        const RayCoherence coherence =
            b.phase == kCamera ? RayCoherence::kCoherent : RayCoherence::kIncoherent;
        if (b.as_planes())
          accel.intersect_planes(b.plane_view(), hits, coherence);
        else
          accel.intersect_batch(b.rays, hits, coherence);
        seconds[b.phase] += thread_seconds() - t0;
        for (const Hit& h : hits) checksum = checksum * 31 + h.prim;
      }
    }
    return seconds;
  }
};

}  // namespace
}  // namespace tuneray

namespace {

int replay_main(int argc, char** argv) {
  using namespace tuneray;
  const std::string first = argc >= 2 ? argv[1] : "";
  if (argc < 2 || first == "--help" || first == "-h") {
    std::fprintf(stderr,
                 "usage: batch_replay SCENE [--scenes-dir D] [--bvh C] [--size WxH] [--spp N] "
                 "[--repeats R] [--only camera|bounce|shadow] [--pollute KiB] [--single 0|1] "
                 "[--ab-env VAR=VALUE] [--ab-copies N] [--native-b PARAMS] [--camera N] "
                 "[--path-camera K/N] [--ray-weight W] [--ray-sample N] [--train-spp K]\n");
    return argc < 2 ? 2 : 0;
  }
  std::string scene_spec = argv[1], scenes_dir, bvh, ab_env;
  std::optional<std::string> native_b;
  int width = 640, height = 360, spp = 4, repeats = 5, pollute_kib = 0, single = 0, ab_copies = 1;
  int only = -1;
  float ray_weight = 0.0f;
  int ray_sample_size = 4096, train_spp = 1;
  long camera = 0;
  bool camera_given = false;
  std::optional<std::pair<long, long>> path_camera;  // K of N along the camera path
  if ((argc - 2) % 2 != 0) {
    std::fprintf(stderr, "batch_replay: option %s needs a value\n", argv[argc - 1]);
    return 2;
  }
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--scenes-dir") {
      scenes_dir = value;
    } else if (key == "--bvh") {
      bvh = value;
    } else if (key == "--size") {
      try {
        std::tie(width, height) = parse_size(value);
      } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "batch_replay: %s\n", e.what());
        return 2;
      }
    } else if (key == "--camera") {
      char* end = nullptr;
      camera = std::strtol(value.c_str(), &end, 10);
      camera_given = true;
      if (end == value.c_str() || *end != '\0' || camera < 0) {
        std::fprintf(stderr, "batch_replay: --camera takes a camera index, not '%s'\n",
                     value.c_str());
        return 2;
      }
    } else if (key == "--path-camera") {
      char* end = nullptr;
      const long k = std::strtol(value.c_str(), &end, 10);
      long n = 0;
      if (end != value.c_str() && *end == '/') {
        const char* count = end + 1;
        n = std::strtol(count, &end, 10);
        if (end == count) n = 0;
      }
      if (*end != '\0' || n < 1 || n > 100000 || k < 0 || k >= n) {
        std::fprintf(stderr,
                     "batch_replay: --path-camera takes K/N with 0 <= K < N (camera K of N "
                     "along the camera path), not '%s'\n",
                     value.c_str());
        return 2;
      }
      path_camera = {k, n};
    } else if (key == "--spp" || key == "--repeats" || key == "--pollute") {
      char* end = nullptr;
      const long n = std::strtol(value.c_str(), &end, 10);
      const long lowest = key == "--pollute" ? 0 : 1;
      if (end == value.c_str() || *end != '\0' || n < lowest || n > 1 << 20) {
        std::fprintf(stderr, "batch_replay: %s takes a whole number from %ld to %d, not '%s'\n",
                     key.c_str(), lowest, 1 << 20, value.c_str());
        return 2;
      }
      int& target = key == "--spp" ? spp : (key == "--repeats" ? repeats : pollute_kib);
      target = static_cast<int>(n);
    } else if (key == "--only") {
      for (int p = 0; p < kPhases; ++p)
        if (value == kPhaseName[p]) only = p;
      if (only < 0) {
        std::fprintf(stderr, "batch_replay: --only takes camera, bounce or shadow, not '%s'\n",
                     value.c_str());
        return 2;
      }
    } else if (key == "--ray-weight") {
      char* end = nullptr;
      ray_weight = std::strtof(value.c_str(), &end);
      if (end == value.c_str() || *end != '\0' || !(ray_weight > 0.0f && ray_weight <= 1.0f)) {
        std::fprintf(stderr, "batch_replay: --ray-weight takes a number in (0, 1], not '%s'\n",
                     value.c_str());
        return 2;
      }
    } else if (key == "--ray-sample" || key == "--train-spp") {
      char* end = nullptr;
      const long n = std::strtol(value.c_str(), &end, 10);
      if (end == value.c_str() || *end != '\0' || n < 1 || n > 1 << 24) {
        std::fprintf(stderr, "batch_replay: %s takes a whole number from 1 to %d, not '%s'\n",
                     key.c_str(), 1 << 24, value.c_str());
        return 2;
      }
      (key == "--ray-sample" ? ray_sample_size : train_spp) = static_cast<int>(n);
    } else if (key == "--ab-env") {
      ab_env = value;
    } else if (key == "--native-b") {
      native_b = value;
    } else if (key == "--ab-copies") {
      ab_copies = std::max(1, std::atoi(value.c_str()));
    } else if (key == "--single") {
      single = std::atoi(value.c_str());
    } else {
      std::fprintf(stderr, "unknown option %s\n", key.c_str());
      return 2;
    }
  }
  if (ray_weight > 0.0f && (!ab_env.empty() || native_b)) {
    std::fprintf(stderr,
                 "batch_replay: --ray-weight takes the second column; give it without "
                 "--ab-env and --native-b\n");
    return 2;
  }
  if (camera_given && path_camera) {
    std::fprintf(stderr, "batch_replay: give --camera or --path-camera, not both\n");
    return 2;
  }
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  LoadOptions load;
  load.scenes_dir = scenes_dir;
  Scene scene = load_scene(scene_spec, load);
  const GeometryView g{scene.positions.data(), scene.positions.size(), scene.triangles.data(),
                       scene.triangles.size()};
  EmbreeNativeAccel native;
  native.build(g);
  TunedBvhAccel tuned(parse_bvh_config(bvh));
  const BuildStats tuned_stats = tuned.build(g);
  std::printf("tuned: build %.0f ms; %zu nodes; %s\n", tuned_stats.build_ms, tuned_stats.node_count,
              tuned_stats.notes.c_str());
  std::unique_ptr<Accel> second;
  if (native_b) {
    second = make_accel("native", *native_b);
    second->build(g);
    std::printf("second backend (the tuned column): native %s\n", second->describe().c_str());
  }
  // --ab-env VAR=VALUE: a second tuned backend built with that environment variable set, replayed
  // in the same rotation (an A/B of a library switch on the same rays in one process).
  // Each variant is built --ab-copies times (trees at different addresses, whose cache and page
  // placement alone moves a replay by several per cent) and timed as the sum over its copies.
  std::vector<std::unique_ptr<TunedBvhAccel>> copies_a, copies_b;
  if (!ab_env.empty()) {
    for (int k = 1; k < ab_copies; ++k) {
      copies_a.push_back(std::make_unique<TunedBvhAccel>(parse_bvh_config(bvh)));
      copies_a.back()->build(g);
    }
    const size_t eq = ab_env.find('=');
    setenv(ab_env.substr(0, eq).c_str(), ab_env.substr(eq + 1).c_str(), 1);
    for (int k = 0; k < ab_copies; ++k) {
      copies_b.push_back(std::make_unique<TunedBvhAccel>(parse_bvh_config(bvh)));
      copies_b.back()->build(g);
    }
  }

  RecordingAccel recorder(native);
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  std::unique_ptr<Sampler> sampler = make_sampler(settings.quality.sampler, 0);
  CameraDesc view;
  if (path_camera) {
    view = cameras_along_path(scene, 0, static_cast<int>(path_camera->second))
               .at(static_cast<size_t>(path_camera->first));
    std::printf("camera %ld of %ld along the camera path: position (%g, %g, %g), fov %g\n",
                path_camera->first, path_camera->second, view.position.x, view.position.y,
                view.position.z, view.vfov_deg);
  } else {
    if (static_cast<size_t>(camera) >= scene.cameras.size()) {
      std::fprintf(stderr, "batch_replay: %s has %zu camera(s); --camera %ld is not one of them\n",
                   scene_spec.c_str(), scene.cameras.size(), camera);
      return 2;
    }
    view = scene.cameras[static_cast<size_t>(camera)];
  }
  TileRenderer renderer(scene, recorder, view, settings, *sampler);
  Film film(width, height);
  for (int s = 0; s < spp; ++s) renderer.render_pass(film, static_cast<uint32_t>(s), 1);
  if (ray_weight > 0.0f) {
    // The sample comes from other passes of the same view than the replayed ones; each segment
    // ends where native Embree finds the ray's hit (shadow rays at their light).
    RecordingAccel trainer(native);
    TileRenderer train(scene, trainer, view, settings, *sampler);
    Film train_film(width, height);
    for (int s = 0; s < train_spp; ++s)
      train.render_pass(train_film, static_cast<uint32_t>(spp + s), 1);
    size_t total = 0;
    for (const Batch& b : trainer.batches) total += b.rays.size();
    const size_t stride = std::max<size_t>(1, total / static_cast<size_t>(ray_sample_size));
    auto sample = std::make_shared<bvh::RaySample>();
    size_t index = 0;
    for (const Batch& b : trainer.batches) {
      for (const Ray& r : b.rays) {
        if (index++ % stride != 0) continue;
        float length = r.tfar;
        if (b.phase != kShadow) {
          Hit h;
          native.intersect(r, h);
          length = h.t;
        }
        sample->add(r, length);
      }
    }
    BvhConfig weighted = parse_bvh_config(bvh);
    weighted.ray_weight = ray_weight;
    for (int k = 1; k < ab_copies; ++k) {
      copies_a.push_back(std::make_unique<TunedBvhAccel>(parse_bvh_config(bvh)));
      copies_a.back()->build(g);
    }
    for (int k = 0; k < ab_copies; ++k) {
      copies_b.push_back(std::make_unique<TunedBvhAccel>(weighted));
      copies_b.back()->set_ray_sample(sample);
      const BuildStats stats = copies_b.back()->build(g);
      if (k == 0)
        std::printf("weighted: %zu segments of %zu rays; build %.0f ms; %zu nodes; %s\n",
                    sample->size(), total, stats.build_ms, stats.node_count, stats.notes.c_str());
    }
    ab_env = "ray_weight=" + std::to_string(ray_weight);
  }
  const bool ab = !copies_b.empty();
  size_t rays[kPhases] = {};
  for (const Batch& b : recorder.batches) rays[b.phase] += b.rays.size();
  const bvh::TreeStats& ts = tuned.tree_stats();
  std::printf(
      "%s: %zu triangles, tuned %s: %zu nodes, %zu leaves, %.2f triangles a leaf; kernels %s\n",
      scene_spec.c_str(), scene.triangles.size(), tuned.describe().c_str(), ts.node_count,
      ts.leaf_count, static_cast<double>(ts.references) / static_cast<double>(ts.leaf_count),
      bvh::to_string(bvh::kernel_isa()));

  Replayer replay;
  replay.batches = &recorder.batches;
  replay.only = only;
  replay.junk.assign(static_cast<size_t>(pollute_kib) << 10, 1);
  SingleRayAccel native_single(native);
  std::vector<double> times[4][kPhases];
  uint64_t sums[4] = {};
  std::vector<const Accel*> group[4] = {
      {&native}, {second ? second.get() : &tuned}, {&native_single}, {}};
  for (const auto& c : copies_a) group[1].push_back(c.get());
  for (const auto& c : copies_b) group[3].push_back(c.get());
  for (int r = -1; r < repeats; ++r) {  // r = -1 warms up
    for (int a = 0; a < 4; ++a) {
      const int which = (r & 1) ? 3 - a : a;  // alternate the order
      if (which == 2 && !single) continue;
      if (group[which].empty()) continue;
      std::vector<double> s(kPhases, 0.0);
      for (const Accel* accel : group[which]) {
        const std::vector<double> one = replay.run(*accel, sums[which]);
        for (int p = 0; p < kPhases; ++p) s[p] += one[p] / static_cast<double>(group[which].size());
      }
      if (r < 0) continue;
      for (int p = 0; p < kPhases; ++p) times[which][p].push_back(s[p]);
    }
  }
  // Medians, and the lowest of the repeats (the least disturbed by other jobs on the machine).
  std::printf("%-7s %9s %10s %10s %7s %10s %10s %7s %10s\n", "phase", "rays", "native ms",
              "tuned ms", "n/t", "native lo", "tuned lo", "n/t lo", "nat 1/call");
  for (int p = 0; p < kPhases; ++p) {
    if (only >= 0 && p != only) continue;  // not replayed
    const double n = median(times[0][p]) * 1e3, t = median(times[1][p]) * 1e3;
    const double nl = lowest(times[0][p]) * 1e3, tl = lowest(times[1][p]) * 1e3;
    std::printf("%-7s %9zu %10.2f %10.2f %7.3f %10.2f %10.2f %7.3f %10.2f\n", kPhaseName[p],
                rays[p], n, t, n / t, nl, tl, nl / tl, median(times[2][p]) * 1e3);
  }
  if (ab) {
    for (int p = 0; p < kPhases; ++p) {
      if (only >= 0 && p != only) continue;
      const double t = median(times[1][p]) * 1e3, b = median(times[3][p]) * 1e3;
      const double tl = lowest(times[1][p]) * 1e3, bl = lowest(times[3][p]) * 1e3;
      std::printf("ab %-7s tuned %10.2f  %s %10.2f  a/b %7.3f  lowest a/b %7.3f\n", kPhaseName[p],
                  t, ab_env.c_str(), b, t / b, tl / bl);
    }
    std::printf("ab checksum %016llx\n", static_cast<unsigned long long>(sums[3]));
  }
  // Variants of the tuned kernels must give the same answers: compare this across binaries.
  std::printf("tuned answers checksum %016llx\n", static_cast<unsigned long long>(sums[1]));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return replay_main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "batch_replay: %s\n", e.what());
    return 1;
  }
}
