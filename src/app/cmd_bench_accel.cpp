#include "app/cmd_bench_accel.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <time.h>
#include <unistd.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "accel/build_bench.h"
#include "accel/embree_native.h"
#include "accel/tuned_bvh.h"
#include "app/cli_parse.h"
#include "app/scene_paths.h"
#include "math/rng.h"
#include "scene/load.h"
#include "tuning/render_vs_native.h"
#include "tuning/stats.h"

namespace tuneray {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

size_t resident_kib() {
  std::ifstream statm("/proc/self/statm");
  size_t pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * static_cast<size_t>(sysconf(_SC_PAGESIZE)) / 1024;
}

GeometryView view_of(const Scene& s) {
  return {s.positions.data(), s.positions.size(), s.triangles.data(), s.triangles.size()};
}

struct RaySet {
  std::string name;
  bool shadow = false;
  std::vector<Ray> rays;
};

Vec3f triangle_normal(const Scene& s, uint32_t prim) {
  const Triangle& t = s.triangles[prim];
  Vec3f n =
      cross(s.positions[t.v[1]] - s.positions[t.v[0]], s.positions[t.v[2]] - s.positions[t.v[0]]);
  float len = length(n);
  return len > 0 ? n / len : Vec3f(0, 0, 1);
}

Vec3f cosine_direction(Vec3f n, Pcg32& rng) {
  float r = std::sqrt(rng.next_float()), phi = 2 * kPi * rng.next_float();
  Vec3f t = std::fabs(n.x) > 0.5f ? normalize(cross(n, Vec3f(0, 1, 0)))
                                  : normalize(cross(n, Vec3f(1, 0, 0)));
  Vec3f b = cross(n, t);
  float z = std::sqrt(std::max(0.0f, 1 - r * r));
  return normalize(t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * z);
}

// Primary rays through the first camera in 8x8 pixel tiles (coherent order); bounce rays from
// their hits with cosine-distributed directions; shadow rays from the hits to points on emissive
// triangles, point lights, or (neither) a point above the scene.
std::vector<RaySet> make_ray_sets(const Scene& scene, const Accel& reference, size_t count) {
  const CameraDesc& cam = scene.cameras.front();
  const int width = std::max(8, static_cast<int>(std::sqrt(count * 16.0 / 9.0)) / 8 * 8);
  const int height = std::max(8, static_cast<int>(count / width) / 8 * 8);
  Vec3f forward = normalize(cam.target - cam.position);
  Vec3f right = normalize(cross(forward, cam.up));
  Vec3f up = cross(right, forward);
  float tan_half = std::tan(cam.vfov_deg * kPi / 360.0f);
  float aspect = float(width) / float(height);

  RaySet primary{"primary", false, {}}, bounce{"incoherent", false, {}}, shadow{"shadow", true, {}};
  Pcg32 rng(7);
  for (int ty = 0; ty < height; ty += 8) {
    for (int tx = 0; tx < width; tx += 8) {
      for (int y = ty; y < ty + 8; ++y) {
        for (int x = tx; x < tx + 8; ++x) {
          float px = (2 * (x + rng.next_float()) / width - 1) * tan_half * aspect;
          float py = (1 - 2 * (y + rng.next_float()) / height) * tan_half;
          primary.rays.push_back(
              {cam.position, 0, normalize(forward + right * px + up * py), kInf});
        }
      }
    }
  }
  std::vector<uint32_t> emissive;
  for (uint32_t i = 0; i < scene.triangles.size(); ++i) {
    uint32_t m = scene.material_ids.empty() ? 0 : scene.material_ids[i];
    if (m < scene.materials.size() && scene.materials[m].is_emissive()) emissive.push_back(i);
  }
  BBox box;
  for (const Vec3f& p : scene.positions) box.extend(p);
  const float eps = 1e-4f * box.diagonal();
  // Hits of the primary rays are the path vertices; cycle through them until each set is full.
  std::vector<std::pair<Vec3f, Vec3f>> vertices;  // position, normal facing the incoming ray
  for (const Ray& r : primary.rays) {
    Hit h;
    if (!reference.intersect(r, h)) continue;
    Vec3f n = triangle_normal(scene, h.prim);
    if (dot(n, r.dir) > 0) n = -n;
    vertices.push_back({r.org + r.dir * h.t, n});
  }
  if (vertices.empty()) vertices.push_back({box.center(), Vec3f(0, 1, 0)});
  for (size_t i = 0; i < count; ++i) {
    auto [p, n] = vertices[i % vertices.size()];
    bounce.rays.push_back({p + n * eps, 0, cosine_direction(n, rng), kInf});
    Vec3f light;
    if (!emissive.empty()) {
      const Triangle& t = scene.triangles[emissive[rng.next_u32() % emissive.size()]];
      float u = rng.next_float(), v = rng.next_float();
      if (u + v > 1) u = 1 - u, v = 1 - v;
      Vec3f a = scene.positions[t.v[0]];
      light = a + (scene.positions[t.v[1]] - a) * u + (scene.positions[t.v[2]] - a) * v;
    } else if (!scene.point_lights.empty()) {
      light = scene.point_lights[rng.next_u32() % scene.point_lights.size()].position;
    } else {
      light = box.center() + Vec3f(0, box.diagonal(), 0);
    }
    Vec3f d = light - p;
    float len = length(d);
    if (len <= 2 * eps) continue;
    shadow.rays.push_back({p + n * eps, 0, d / len, len - 2 * eps});
  }
  return {std::move(primary), std::move(bounce), std::move(shadow)};
}

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + ts.tv_nsec * 1e-9;
}

// Seconds for one pass over the set, all threads: wall time, or the CPU time of all threads
// (which other processes on a shared machine do not inflate by taking turns on the cores).
double trace_seconds(const Accel& accel, const RaySet& set, bool cpu_time = false) {
  std::atomic<size_t> sink{0};
  const double cpu_start = cpu_time ? cpu_seconds() : 0.0;
  auto start = Clock::now();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, set.rays.size(), 1024),
                    [&](const tbb::blocked_range<size_t>& range) {
                      size_t hits = 0;
                      for (size_t i = range.begin(); i < range.end(); ++i) {
                        if (set.shadow) {
                          hits += accel.occluded(set.rays[i]);
                        } else {
                          Hit h;
                          hits += accel.intersect(set.rays[i], h);
                        }
                      }
                      sink += hits;
                    });
  double s = cpu_time ? cpu_seconds() - cpu_start : ms_since(start) / 1000.0;
  return sink.load() == size_t(-1) ? 0 : s;
}

// Branching 4 and 8, leaf sizes 1-8, high quality. sah_block_size=4 makes the SAH count leaf
// cost in packs of 4, which is how our leaves store triangles.
std::vector<std::string> sweep_configs(const std::string& base) {
  std::vector<std::string> out = {base};
  for (int width : {4, 8}) {
    const std::string w = "branching=" + std::to_string(width);
    out.push_back(w + ",max_leaf=1");
    out.push_back(w + ",max_leaf=4");
    for (int leaf : {4, 8}) out.push_back(w + ",sah_block_size=4,max_leaf=" + std::to_string(leaf));
  }
  const std::string best_guess = "branching=8,sah_block_size=4,max_leaf=8";
  out.push_back(best_guess + ",quality=high");
  out.push_back(best_guess + ",static=1");
  out.push_back(best_guess + ",compact=1");
  return out;
}

std::vector<std::string> scene_list(const BenchAccelArgs& args) {
  if (!args.scenes.empty()) return args.scenes;
  return shared_scene_files(find_shared_scenes_dir(args.scenes_dir));
}

std::unique_ptr<tbb::global_control> limit_threads(int threads) {
  if (threads <= 0) return nullptr;
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                               threads);
}

nlohmann::json stats_json(const BuildStats& s) {
  return {{"build_ms", s.build_ms},
          {"memory_bytes", s.memory_bytes},
          {"node_count", s.node_count},
          {"leaf_count", s.leaf_count},
          {"depth", s.depth},
          {"sah_cost", s.sah_cost},
          {"notes", s.notes}};
}

bool write_json(const std::string& path, const nlohmann::json& j) {
  if (path.empty()) return true;
  std::ofstream out(path);
  if (!out) {
    std::fprintf(stderr, "bench: cannot write '%s'\n", path.c_str());
    return false;
  }
  out << j.dump(2) << "\n";
  return true;
}

// The render-level run after a scene's table: native Embree against the database's best
// configuration for the scene's camera, or else the table's best on incoherent rays.
nlohmann::json render_run(const BenchAccelArgs& args, const Scene& scene, const BvhConfig& best) {
  RenderVsNativeOptions o;
  std::tie(o.width, o.height) = parse_size(args.size);
  o.spp = args.spp;
  o.repeats = std::max(1, args.repeats);
  o.wavefront = args.scheduler == "wavefront";
  const CameraDesc& camera = scene.cameras.front();
  AccelChoice chosen = AccelChoice::tuned(best);
  std::string source = "best of the table on incoherent rays";
  if (!args.db.empty()) {
    auto found = best_in_database(args.db, scene, camera, o);
    if (!found)
      throw std::runtime_error("bench traversal: " + args.db + " holds no `tune --objective " +
                               "render` data for " + args.size + ", " + std::to_string(o.spp) +
                               " spp, " + args.scheduler + " on this machine");
    chosen = found->choice;
    source = "best in " + args.db + " (" + found->tuning_key + ")";
  }
  RenderVsNative r = render_vs_native(scene, camera, chosen, o);
  std::printf(
      "render %dx%d, %u spp, %s scheduler, first camera, median of %d: native %.2f ms, "
      "chosen %.2f ms -> %.3fx native\n  chosen: %s\n  (%s)\n",
      o.width, o.height, o.spp, args.scheduler.c_str(), o.repeats, r.native_median_ms,
      r.chosen_median_ms, r.speedup(), r.config.c_str(), source.c_str());
  std::fflush(stdout);
  return {{"size", args.size},
          {"spp", o.spp},
          {"scheduler", args.scheduler},
          {"repeats", o.repeats},
          {"config", r.config},
          {"source", source},
          {"native_ms", r.native_ms},
          {"chosen_ms", r.chosen_ms},
          {"native_median_ms", r.native_median_ms},
          {"chosen_median_ms", r.chosen_median_ms},
          {"native_build_ms", r.native_build_ms},
          {"chosen_build_ms", r.chosen_build_ms},
          {"speedup_over_native", r.speedup()}};
}

}  // namespace

int run_bench_traversal(const BenchAccelArgs& args) {
  auto threads = limit_threads(args.threads);
  const int repeats = std::max(1, args.repeats);
  const BvhConfig base = parse_bvh_config(args.bvh);
  if (args.render) parse_size(args.size);  // a bad size fails now, not after the tables
  auto scenes = scene_list(args);
  if (scenes.empty()) {
    std::fprintf(stderr, "bench traversal: no scene given and no shared scenes found\n");
    return 1;
  }
  nlohmann::json report = {{"rays_per_set", args.rays}, {"repeats", repeats}, {"scenes", {}}};
  for (const std::string& spec : scenes) {
    Scene scene = load_scene(spec, LoadOptions{args.scenes_dir});
    GeometryView g = view_of(scene);
    EmbreeNativeAccel native;
    BuildStats native_stats = native.build(g);
    auto sets = make_ray_sets(scene, native, args.rays);
    std::printf("\n%s: %zu triangles, native build %.1f ms, %zu/%zu/%zu rays\n", spec.c_str(),
                g.triangle_count, native_stats.build_ms, sets[0].rays.size(), sets[1].rays.size(),
                sets[2].rays.size());
    std::printf("%-52s %9s %8s %8s %7s %8s | %-26s | %-26s | %-26s\n", "config", "build ms",
                "nodes", "leaves", "SAH", "MiB", "primary nat/tuned/ratio",
                "incoherent nat/tuned/ratio", "shadow nat/tuned/ratio");
    nlohmann::json scene_json = {{"scene", spec},
                                 {"triangles", g.triangle_count},
                                 {"native_build_ms", native_stats.build_ms},
                                 {"configs", nlohmann::json::array()}};
    auto configs = args.sweep ? sweep_configs(base.to_string()) : std::vector{base.to_string()};
    double best_incoherent = 0;
    std::string best_config;
    BvhConfig best_bvh = base;
    for (const std::string& text : configs) {
      TunedBvhAccel tuned(parse_bvh_config(text));
      BuildStats stats;
      try {
        stats = tuned.build(g);
      } catch (const BuildError& e) {
        std::printf("%-52s refused: %s\n", text.c_str(), e.what());
        continue;
      }
      nlohmann::json cj = stats_json(stats);
      cj["config"] = tuned.describe();
      std::string label = text == BvhConfig{}.to_string() ? "(defaults)" : text;
      std::printf("%-52s %9.1f %8zu %8zu %7.2f %8.1f |", label.c_str(), stats.build_ms,
                  stats.node_count, stats.leaf_count, stats.sah_cost,
                  stats.memory_bytes / 1048576.0);
      for (const RaySet& set : sets) {
        std::vector<double> nat, tun;
        trace_seconds(native, set);  // warm caches
        trace_seconds(tuned, set);
        for (int r = 0; r < repeats; ++r) {
          nat.push_back(trace_seconds(native, set, args.cpu_time));
          tun.push_back(trace_seconds(tuned, set, args.cpu_time));
        }
        double n_mrays = set.rays.size() / median(nat) / 1e6;
        double t_mrays = set.rays.size() / median(tun) / 1e6;
        cj["ray_sets"][set.name] = {
            {"native_mrays", n_mrays}, {"tuned_mrays", t_mrays}, {"ratio", t_mrays / n_mrays}};
        std::printf(" %7.2f %7.2f %6.3f     |", n_mrays, t_mrays, t_mrays / n_mrays);
        if (set.name == "incoherent" && t_mrays / n_mrays > best_incoherent) {
          best_incoherent = t_mrays / n_mrays;
          best_config = tuned.describe();
          best_bvh = tuned.config();
        }
      }
      std::printf("\n");
      std::fflush(stdout);
      scene_json["configs"].push_back(cj);
    }
    scene_json["best_incoherent"] = {{"config", best_config}, {"ratio", best_incoherent}};
    std::printf("best on incoherent rays: %s (ratio %.3f)\n", best_config.c_str(), best_incoherent);
    if (args.render) scene_json["render"] = render_run(args, scene, best_bvh);
    report["scenes"].push_back(scene_json);
    // After every scene, so an interrupted run keeps what it measured.
    if (!write_json(args.json, report)) return 1;
  }
  return write_json(args.json, report) ? 0 : 1;
}

int run_bench_build(const BenchAccelArgs& args) {
  auto threads = limit_threads(args.threads);
  const int repeats = std::max(1, args.repeats);
  const BvhConfig base = parse_bvh_config(args.bvh);
  auto scenes = scene_list(args);
  if (scenes.empty()) {
    std::fprintf(stderr, "bench build: no scene given and no shared scenes found\n");
    return 1;
  }
  std::vector<std::string> configs = {base.to_string()};
  if (args.sweep) {
    for (const char* q : {"low", "medium", "high"}) {
      for (int width : {2, 4, 8}) {
        configs.push_back(std::string("quality=") + q + ",branching=" + std::to_string(width));
      }
    }
    configs.push_back("branching=8,static=1");
    configs.push_back("branching=8,compact=1");
  }
  nlohmann::json report = {{"repeats", repeats}, {"scenes", {}}};
  for (const std::string& spec : scenes) {
    Scene scene = load_scene(spec, LoadOptions{args.scenes_dir});
    GeometryView g = view_of(scene);
    std::printf(
        "\n%s: %zu triangles; native = Embree's own build at the same quality, "
        "interleaved with the tuned one, medians of %d\n",
        spec.c_str(), g.triangle_count, repeats);
    std::printf("%-52s %9s %9s %6s %8s %8s %6s %8s %8s %10s\n", "config", "build ms", "native",
                "ratio", "nodes", "leaves", "depth", "SAH", "MiB", "RSS KiB");
    nlohmann::json scene_json = {
        {"scene", spec}, {"triangles", g.triangle_count}, {"configs", nlohmann::json::array()}};
    EmbreeNativeAccel native;
    TunedBvhAccel tuned;  // one accelerator rebuilt with every configuration, as the tuner does
    for (const std::string& text : configs) {
      tuned.set_config(parse_bvh_config(text));
      BuildComparison c;
      try {
        c = compare_build_times(g, tuned, native, repeats);
      } catch (const BuildError& e) {
        std::printf("%-52s refused: %s\n", text.c_str(), e.what());
        continue;
      }
      const BuildStats& stats = c.tuned;
      nlohmann::json cj = stats_json(stats);
      cj["config"] = tuned.describe();
      cj["native"] = native.describe();
      cj["native_build_ms"] = c.native_median_ms;
      cj["ratio"] = c.ratio;
      cj["tuned_ms_runs"] = c.tuned_ms;
      cj["native_ms_runs"] = c.native_ms;
      cj["rss_kib"] = resident_kib();
      std::printf("%-52s %9.1f %9.1f %6.2f %8zu %8zu %6d %8.2f %8.1f %10zu  %s\n", text.c_str(),
                  stats.build_ms, c.native_median_ms, c.ratio, stats.node_count, stats.leaf_count,
                  stats.depth, stats.sah_cost, stats.memory_bytes / 1048576.0, resident_kib(),
                  stats.notes.c_str());
      std::fflush(stdout);
      scene_json["configs"].push_back(cj);
    }
    report["scenes"].push_back(scene_json);
  }
  return write_json(args.json, report) ? 0 : 1;
}

}  // namespace tuneray
