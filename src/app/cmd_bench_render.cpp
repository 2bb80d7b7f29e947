// tuneray bench render: bench/render_bench.h's speeds per scene and the Embree comparison as a
// table, and as JSON when asked.
#include <fmt/core.h>
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "accel/factory.h"
#include "app/commands.h"
#include "bench/scene_paths.h"
#include "image/atomic_file.h"
#include "scene/load.h"
#include "tuning/stats.h"

namespace tuneray {

namespace {

void print_embree(const EmbreeComparison& c) {
  fmt::print("  {:<12} {:>10} {:>12}\n", "", "frame ms", "Mrays/s*");
  fmt::print("  {:<12} {:>10.1f} {:>12.2f}  {}\n", "tuneray", median(c.our_frame_ms), c.our_mrays,
             c.our_accel);
  fmt::print("  {:<12} {:>10.1f} {:>12.2f}\n", "embree", median(c.embree_frame_ms), c.embree_mrays);
  const std::vector<double> ratios = c.speed_ratios();
  fmt::print(
      "  speed ratio tuneray/embree (frame time) = {:.2f}, median of {} interleaved repeats "
      "(range {:.2f}-{:.2f}; each: {:.2f})\n",
      c.speed_ratio(), ratios.size(), *std::min_element(ratios.begin(), ratios.end()),
      *std::max_element(ratios.begin(), ratios.end()), fmt::join(ratios, " "));
  fmt::print(
      "  frame ms are medians; * each program counts rays its own way: compare frame times.\n");
}

}  // namespace

int run_bench_render(const RenderBenchOptions& a) {
  make_accel(a.accel, a.bvh);  // a bad backend or parameter fails before any table is printed
  LoadOptions load_options;
  load_options.scenes_dir = find_shared_scenes_dir(a.scenes_dir);
  nlohmann::json json = {{"size", std::to_string(a.width) + "x" + std::to_string(a.height)},
                         {"spp", a.spp},
                         {"repeats", a.repeats},
                         {"max_bounces", a.max_bounces},
                         {"accel", a.accel},
                         {"bvh", a.bvh},
                         {"scenes", nlohmann::json::array()}};
  fmt::print("{:<28} {:>10} {:>10} {:>11} {:>9}  {}\n", "scene", "triangles", "build ms",
             "ms per spp", "Mrays/s", "accel");
  for (const std::string& spec : render_bench_scenes(a)) {
    Scene scene = load_scene(spec, load_options);
    std::string name = std::filesystem::path(spec).stem().string();
    RenderSpeed r = measure_render_speed(name, scene, a, a.spp);
    fmt::print("{:<28} {:>10} {:>10.1f} {:>11.2f} {:>9.2f}  {}\n", r.scene, r.triangles, r.build_ms,
               r.ms_per_spp, r.mrays, r.accel);
    json["scenes"].push_back({{"scene", r.scene},
                              {"accel", r.accel},
                              {"triangles", r.triangles},
                              {"build_ms", r.build_ms},
                              {"ms_per_spp", r.ms_per_spp},
                              {"mrays_per_s", r.mrays}});
  }

  if (a.embree_reference) {
    fmt::print(
        "\nEmbree's tutorial pathtracer, same scene/camera/size/spp/path length, same run:\n");
    EmbreeComparison c = compare_with_embree(a);
    if (!c.ok) {
      fmt::print("  skipped: {}\n", c.error);
    } else {
      print_embree(c);
      json["embree_reference"] = {{"spp", c.spp},
                                  {"tuneray_accel", c.our_accel},
                                  {"tuneray_frame_ms", median(c.our_frame_ms)},
                                  {"embree_frame_ms", median(c.embree_frame_ms)},
                                  {"tuneray_frame_ms_per_repeat", c.our_frame_ms},
                                  {"embree_frame_ms_per_repeat", c.embree_frame_ms},
                                  {"speed_ratio_per_repeat", c.speed_ratios()},
                                  {"tuneray_mrays", c.our_mrays},
                                  {"embree_mrays", c.embree_mrays},
                                  {"speed_ratio", c.speed_ratio()}};
    }
  }
  if (!a.json.empty()) {
    write_text_file(a.json, json.dump(2) + "\n");
    fmt::print("wrote {}\n", a.json);
  }
  return 0;
}

}  // namespace tuneray
