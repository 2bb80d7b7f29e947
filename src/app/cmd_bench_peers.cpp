// tuneray bench peers: bench/peers_bench.h's equal-time comparison as a table, and as JSON when
// asked.
#include <fmt/core.h>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "image/atomic_file.h"

namespace tuneray {

namespace {

void print_result(const PeersBenchOptions& o, const PeersResult& r) {
  fmt::print("\nEmbree's pathtracer frames (median of {} interleaved repeats):\n", o.repeats);
  fmt::print("  {:>6} {:>10} {:>9}\n", "spp", "frame ms", "RMSE");
  for (const PeerPoint& p : r.embree)
    fmt::print("  {:>6} {:>10.1f} {:>9.5f}\n", p.spp, p.frame_ms, p.rmse);
  fmt::print("tuneray ({} accel{}{}, default quality switches): {:.2f} ms per spp\n", o.accel,
             o.bvh.empty() ? "" : " ", o.bvh, r.ours_ms_per_spp);
  fmt::print(
      "tuneray's reference has noise of its own: RMSE {:.5f} ({:.5f} 8-bit) against the truth,\n"
      "from its halves. Below, our errors without it (as the pathtracer's are without its\n"
      "reference's), then as measured.\n\n",
      r.reference_noise_rmse, r.reference_noise_rmse_ldr);
  fmt::print("{:>7} {:>11} {:>11} {:>11} {:>9} {:>11} {:>12}", "time s", "embree RMSE", "tuneray",
             "tuneray 8b", "spp", "ratio raw", "ratio 8-bit");
  if (o.denoise) fmt::print(" {:>14} {:>15}", "denoised raw", "denoised 8-bit");
  if (o.cache.vertex > 0) fmt::print(" {:>12} {:>13}", "cached raw", "cached 8-bit");
  if (o.path_reuse > 0) fmt::print(" {:>12} {:>13}", "reused raw", "reused 8-bit");
  fmt::print("\n");
  for (const PeersRow& row : r.rows) {
    fmt::print("{:>7.2f} {:>11.5f} {:>11.5f} {:>11.5f} {:>9.1f} {:>11.3f} {:>12.3f}", row.time_s,
               row.embree_rmse, row.raw.truth, row.ldr.truth, row.ours_spp, row.ratio(row.raw),
               row.ratio(row.ldr));
    if (o.denoise)
      fmt::print(" {:>14.3f} {:>15.3f}", row.ratio(row.denoised), row.ratio(row.denoised_ldr));
    if (o.cache.vertex > 0)
      fmt::print(" {:>12.3f} {:>13.3f}", row.ratio(row.cached), row.ratio(row.cached_ldr));
    if (o.path_reuse > 0)
      fmt::print(" {:>12.3f} {:>13.3f}", row.ratio(row.reused), row.ratio(row.reused_ldr));
    fmt::print("\n");
  }
  fmt::print(
      "ratio = tuneray RMSE / pathtracer RMSE at equal render time (< 1: tuneray is better).\n"
      "8-bit: tuneray's image and reference through the pathtracer's output transform (clamp to\n"
      "[0,1], floor(255.01 x)/255), as the pathtracer's own numbers are. Denoised: the same\n"
      "runs with --denoise, the filtering counted as frame time (ratios to the pathtracer).\n");
  if (o.cache.vertex > 0)
    fmt::print("Cached: the same runs with the radiance cache (--cache-vertex {}; biased).\n",
               o.cache.vertex);
  if (o.path_reuse > 0)
    fmt::print(
        "Reused: the same runs with path reuse in pools of {} pixels (--path-reuse{}; "
        "unbiased).\n",
        o.path_reuse, o.path_reuse_auto ? " auto: where the runs' own passes show it pays" : "");
  fmt::print("\nAs measured against tuneray's reference (its noise included):\n");
  fmt::print("{:>7} {:>11} {:>11} {:>11} {:>12}", "time s", "tuneray", "tuneray 8b", "ratio raw",
             "ratio 8-bit");
  if (o.denoise) fmt::print(" {:>14} {:>15}", "denoised raw", "denoised 8-bit");
  if (o.cache.vertex > 0) fmt::print(" {:>12} {:>13}", "cached raw", "cached 8-bit");
  if (o.path_reuse > 0) fmt::print(" {:>12} {:>13}", "reused raw", "reused 8-bit");
  fmt::print("\n");
  for (const PeersRow& row : r.rows) {
    fmt::print("{:>7.2f} {:>11.5f} {:>11.5f} {:>11.3f} {:>12.3f}", row.time_s, row.raw.measured,
               row.ldr.measured, row.measured_ratio(row.raw), row.measured_ratio(row.ldr));
    if (o.denoise)
      fmt::print(" {:>14.3f} {:>15.3f}", row.measured_ratio(row.denoised),
                 row.measured_ratio(row.denoised_ldr));
    if (o.cache.vertex > 0)
      fmt::print(" {:>12.3f} {:>13.3f}", row.measured_ratio(row.cached),
                 row.measured_ratio(row.cached_ldr));
    if (o.path_reuse > 0)
      fmt::print(" {:>12.3f} {:>13.3f}", row.measured_ratio(row.reused),
                 row.measured_ratio(row.reused_ldr));
    fmt::print("\n");
  }
}

nlohmann::json to_json(const PeersBenchOptions& o, const PeersResult& r) {
  nlohmann::json j = {{"size", std::to_string(o.peer.width) + "x" + std::to_string(o.peer.height)},
                      {"max_path_length", o.peer.max_path_length},
                      {"reference_spp", o.reference_spp},
                      {"repeats", o.repeats},
                      {"frame_ms", o.frame_ms},
                      {"accel", o.accel},
                      {"bvh", o.bvh},
                      {"denoise_column", o.denoise},
                      {"cache_vertex", o.cache.vertex},
                      {"cache_cell", o.cache.cell},
                      {"cache_train", o.cache.train},
                      {"path_reuse", o.path_reuse},
                      {"path_reuse_auto", o.path_reuse_auto},
                      {"skipped", r.skipped}};
  if (r.skipped) {
    j["reason"] = r.reason;
    return j;
  }
  j["embree_reference"] = r.embree_reference;
  j["tuneray_reference"] = r.ours_reference;
  j["tuneray_reference_noise_rmse"] = r.reference_noise_rmse;
  j["tuneray_reference_noise_rmse_8bit"] = r.reference_noise_rmse_ldr;
  j["tuneray_ms_per_spp"] = r.ours_ms_per_spp;
  j["embree_frames"] = nlohmann::json::array();
  for (const PeerPoint& p : r.embree)
    j["embree_frames"].push_back({{"spp", p.spp}, {"frame_ms", p.frame_ms}, {"rmse", p.rmse}});
  // "rmse" and "ratio": against the truth; "measured_...": against tuneray's reference.
  auto add = [](nlohmann::json& row, const std::string& name, const PeersRow& r,
                const OurError& e) {
    row[name + "_rmse"] = e.truth;
    row[name + "_ratio"] = r.ratio(e);
    row[name + "_measured_rmse"] = e.measured;
    row[name + "_measured_ratio"] = r.measured_ratio(e);
  };
  j["rows"] = nlohmann::json::array();
  for (const PeersRow& row : r.rows) {
    nlohmann::json out = {
        {"time_s", row.time_s}, {"embree_rmse", row.embree_rmse}, {"tuneray_spp", row.ours_spp}};
    add(out, "tuneray", row, row.raw);
    add(out, "tuneray_8bit", row, row.ldr);
    if (o.denoise) {
      add(out, "denoised", row, row.denoised);
      add(out, "denoised_8bit", row, row.denoised_ldr);
    }
    if (o.cache.vertex > 0) {
      add(out, "cached", row, row.cached);
      add(out, "cached_8bit", row, row.cached_ldr);
    }
    if (o.path_reuse > 0) {
      add(out, "reused", row, row.reused);
      add(out, "reused_8bit", row, row.reused_ldr);
    }
    j["rows"].push_back(out);
  }
  return j;
}

}  // namespace

int run_bench_peers(const PeersBenchOptions& options, const std::string& json) {
  check_peers_options(options);
  fmt::print("Equal-time error against Embree's pathtracer: {}x{}, path length {}\n",
             options.peer.width, options.peer.height, options.peer.max_path_length);
  PeersResult r = run_peers_bench(options, [](const std::string& line) {
    fmt::print("  {}\n", line);
    std::fflush(stdout);
  });
  if (r.skipped)
    fmt::print("skipped: {}\n", r.reason);
  else
    print_result(options, r);
  if (!json.empty()) {
    write_text_file(json, to_json(options, r).dump(2) + "\n");
    fmt::print("wrote {}\n", json);
  }
  return 0;
}

}  // namespace tuneray
