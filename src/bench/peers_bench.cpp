#include "bench/peers_bench.h"

#include <fmt/core.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>

#include "accel/factory.h"
#include "bench/equal_time.h"
#include "bench/ground_truth.h"
#include "bench/shown_frames.h"
#include "image/io.h"
#include "image/metrics.h"
#include "scene/load.h"
#include "tuning/stats.h"

namespace tuneray {

namespace {

constexpr int kMostPeerSpp = 4096;

struct OurRun {
  std::vector<double> time_ms, spp, rmse, rmse_ldr;
};

// Frame-budget frames until `total_ms`, with the error of what each frame shows: linear, and
// through the pathtracer's output transform.
OurRun run_ours(const Scene& scene, const Accel& accel, const RenderSettings& settings,
                double frame_ms, double total_ms, const Image& truth, const Image& truth_ldr) {
  OurRun run;
  run_shown_frames(
      scene, accel, scene.cameras.at(0), settings, settings.seed, frame_ms,
      [&](const ShownFrame& f) {
        run.time_ms.push_back(f.time_ms);
        run.spp.push_back(f.spp);
        run.rmse.push_back(compare_images(f.image, truth).rmse);
        run.rmse_ldr.push_back(compare_images(embree_output_transform(f.image), truth_ldr).rmse);
        return f.time_ms < total_ms;
      });
  return run;
}

// Samples per pixel at time t along a run (linear between frames).
double spp_at_time(const OurRun& run, double t) {
  size_t i = 0;
  while (i + 1 < run.time_ms.size() && run.time_ms[i] < t) ++i;
  if (i == 0) return run.spp[0] * t / run.time_ms[0];
  double w = (t - run.time_ms[i - 1]) / (run.time_ms[i] - run.time_ms[i - 1]);
  return run.spp[i - 1] + std::clamp(w, 0.0, 1.0) * (run.spp[i] - run.spp[i - 1]);
}

Image read_peer_image(const EmbreePeer& peer, int spp, const std::string& path) {
  embree_peer_render(peer, spp, path);
  Image image = read_image(path);
  std::error_code ec;
  std::filesystem::remove(path, ec);
  return image;
}

std::string temporary_image_path(int spp) {
  return (std::filesystem::temp_directory_path() /
          fmt::format("tuneray-peer-{}-{}.pfm", static_cast<long>(getpid()), spp))
      .string();
}

}  // namespace

double peer_rmse_against_truth(double rmse_against_reference, int spp, int reference_spp) {
  if (spp >= reference_spp)
    throw std::invalid_argument(
        fmt::format("bench peers: a {}-spp pathtracer frame is part of its {}-spp reference", spp,
                    reference_spp));
  return rmse_against_reference /
         std::sqrt(1.0 - static_cast<double>(spp) / static_cast<double>(reference_spp));
}

void check_peers_options(const PeersBenchOptions& o) {
  auto fail = [](const std::string& what) { throw std::invalid_argument("bench peers: " + what); };
  if (o.peer.width < 1 || o.peer.height < 1) fail("the image size must be positive");
  if (o.peer.max_path_length < 1) fail("--max-bounces must be at least 1");
  if (o.times_s.empty()) fail("--times needs at least one time");
  for (double t : o.times_s)
    if (!(t > 0) || !std::isfinite(t)) fail(fmt::format("time {} is not a positive number", t));
  if (o.reference_spp < 2) fail("--reference-spp must be at least 2");
  if (o.repeats < 1 || o.timing_frames < 1) fail("--repeats must be at least 1");
  if (!(o.frame_ms > 0) || !std::isfinite(o.frame_ms)) fail("--frame-ms must be a positive number");
  if (o.path_reuse < 0 || o.path_reuse == 1)
    fail("--path-reuse must be 0 (off) or a pool of at least 2 pixels");
  make_accel(o.accel, o.bvh);  // an unknown backend or parameter fails before anything runs
}

std::string embree_reference_path(const PeersBenchOptions& o) {
  const EmbreePeer& p = o.peer;
  std::string stem = std::filesystem::path(p.scene).stem().string();
  return (std::filesystem::path(o.truth_dir) / fmt::format("pathtracer-{}-{}x{}-L{}-{}spp.pfm",
                                                           stem, p.width, p.height,
                                                           p.max_path_length, o.reference_spp))
      .string();
}

PeersResult run_peers_bench(const PeersBenchOptions& o, const PeersProgress& progress) {
  check_peers_options(o);
  auto say = [&](const std::string& line) {
    if (progress) progress(line);
  };
  PeersResult result;
  result.reason = embree_peer_missing(o.peer);
  if (!result.reason.empty()) {
    result.skipped = true;
    return result;
  }
  const double max_ms = 1000.0 * *std::max_element(o.times_s.begin(), o.times_s.end());

  // References: each program against its own converged image.
  std::filesystem::create_directories(o.truth_dir);
  result.embree_reference = embree_reference_path(o);
  if (!std::filesystem::exists(result.embree_reference)) {
    say(fmt::format("rendering the pathtracer's {}-spp reference ...", o.reference_spp));
    embree_peer_render(o.peer, o.reference_spp, result.embree_reference);
  }
  Image embree_truth = read_image(result.embree_reference);

  Scene scene = load_scene(o.peer.scene);
  std::unique_ptr<Accel> accel = make_accel(o.accel, o.bvh);
  accel->build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
                scene.triangles.size()});
  GroundTruthKey key;
  key.scene_spec = "embree-peer:" + o.peer.scene;
  key.camera = scene.cameras.at(0);
  key.width = o.peer.width;
  key.height = o.peer.height;
  key.max_bounces = o.peer.max_path_length;
  key.spp = o.reference_spp;
  key.require_halves = true;
  result.ours_reference = ground_truth_path(o.truth_dir, key);
  if (!std::filesystem::exists(result.ours_reference))
    say(fmt::format("rendering tuneray's {}-spp reference ...", o.reference_spp));
  Image ours_truth = ground_truth(o.truth_dir, key, scene, *accel);
  if (embree_truth.width() != o.peer.width || embree_truth.height() != o.peer.height)
    throw std::runtime_error(result.embree_reference + ": not a " + std::to_string(o.peer.width) +
                             "x" + std::to_string(o.peer.height) + " image");
  Image ours_truth_ldr = embree_output_transform(ours_truth);
  const std::optional<GroundTruthHalves> halves = ground_truth_halves(o.truth_dir, key);
  if (!halves) throw std::runtime_error(result.ours_reference + ": its halves are missing");
  const double noise_mse = reference_noise_mse(halves->a, halves->b);
  const double noise_mse_ldr =
      reference_noise_mse(embree_output_transform(halves->a), embree_output_transform(halves->b));
  result.reference_noise_rmse = std::sqrt(noise_mse);
  result.reference_noise_rmse_ldr = std::sqrt(noise_mse_ldr);

  // The pathtracer's frames at 1, 2, 4, ... spp until one frame takes the longest time, and at
  // most half the reference's samples (see peer_rmse_against_truth).
  std::vector<std::vector<double>> embree_ms;  // [spp index][repeat]
  for (int spp = 1; spp <= std::min(kMostPeerSpp, o.reference_spp / 2); spp *= 2) {
    EmbreePeerTiming t = embree_peer_benchmark(o.peer, spp, o.timing_frames);
    result.embree.push_back({spp, 0, 0});
    embree_ms.push_back({t.frame_ms});
    if (t.frame_ms >= max_ms) break;
  }
  say(fmt::format("pathtracer: {} frame sizes, up to {} spp", result.embree.size(),
                  result.embree.back().spp));
  for (PeerPoint& p : result.embree)
    p.rmse = peer_rmse_against_truth(
        compare_images(read_peer_image(o.peer, p.spp, temporary_image_path(p.spp)), embree_truth)
            .rmse,
        p.spp, o.reference_spp);

  RenderSettings settings;
  settings.width = o.peer.width;
  settings.height = o.peer.height;
  settings.max_bounces = o.peer.max_path_length;
  const size_t nt = o.times_s.size();
  std::vector<std::vector<double>> ours_rmse(nt), ours_ldr(nt), ours_spp(nt), denoised(nt),
      denoised_ldr(nt), cached(nt), cached_ldr(nt), reused(nt), reused_ldr(nt);
  std::vector<double> ours_ms_per_spp;
  for (int r = 0; r < o.repeats; ++r) {
    if (r > 0)  // the first repeat's pathtracer timings were taken above
      for (size_t i = 0; i < result.embree.size(); ++i)
        embree_ms[i].push_back(
            embree_peer_benchmark(o.peer, result.embree[i].spp, o.timing_frames).frame_ms);
    settings.seed = 1000 + static_cast<uint64_t>(r);
    OurRun run =
        run_ours(scene, *accel, settings, o.frame_ms, max_ms * 1.05, ours_truth, ours_truth_ldr);
    ours_ms_per_spp.push_back(run.time_ms.back() / run.spp.back());
    for (size_t i = 0; i < nt; ++i) {
      double t = 1000.0 * o.times_s[i];
      ours_rmse[i].push_back(rmse_at_time(run.time_ms, run.rmse, t));
      ours_ldr[i].push_back(rmse_at_time(run.time_ms, run.rmse_ldr, t));
      ours_spp[i].push_back(spp_at_time(run, t));
    }
    // A column's RMSE at each of the times, from one more run with `variant`'s settings.
    auto add_column = [&](const RenderSettings& variant, std::vector<std::vector<double>>& raw,
                          std::vector<std::vector<double>>& ldr) {
      const OurRun v =
          run_ours(scene, *accel, variant, o.frame_ms, max_ms * 1.05, ours_truth, ours_truth_ldr);
      for (size_t i = 0; i < nt; ++i) {
        const double t = 1000.0 * o.times_s[i];
        raw[i].push_back(rmse_at_time(v.time_ms, v.rmse, t));
        ldr[i].push_back(rmse_at_time(v.time_ms, v.rmse_ldr, t));
      }
    };
    if (o.denoise) {
      RenderSettings with_denoiser = settings;
      with_denoiser.quality.denoise = true;
      add_column(with_denoiser, denoised, denoised_ldr);
    }
    if (o.cache.vertex > 0) {
      RenderSettings with_cache = settings;
      with_cache.quality.cache = o.cache;
      add_column(with_cache, cached, cached_ldr);
    }
    if (o.path_reuse > 0) {
      RenderSettings with_reuse = settings;
      with_reuse.quality.path_reuse = o.path_reuse;
      with_reuse.quality.path_reuse_auto = o.path_reuse_auto;
      add_column(with_reuse, reused, reused_ldr);
    }
    say(fmt::format("repeat {}/{} done", r + 1, o.repeats));
  }

  // The curve needs increasing times: a frame of more samples that timed no slower than a
  // smaller one (noise on tiny images) adds nothing to it.
  std::vector<double> embree_time, embree_error;
  for (size_t i = 0; i < result.embree.size(); ++i) {
    result.embree[i].frame_ms = median(embree_ms[i]);
    if (!embree_time.empty() && result.embree[i].frame_ms <= embree_time.back()) continue;
    embree_time.push_back(result.embree[i].frame_ms);
    embree_error.push_back(result.embree[i].rmse);
  }
  result.ours_ms_per_spp = median(ours_ms_per_spp);
  // The correction is monotonic, so it commutes with the median.
  auto column = [](const std::vector<double>& measured, double noise) {
    OurError e;
    if (measured.empty()) return e;  // the denoiser's column, not run
    e.measured = median(measured);
    e.truth = rmse_without_reference_noise(e.measured, noise);
    return e;
  };
  for (size_t i = 0; i < o.times_s.size(); ++i) {
    PeersRow row;
    row.time_s = o.times_s[i];
    row.embree_rmse = rmse_at_time(embree_time, embree_error, 1000.0 * o.times_s[i]);
    row.ours_spp = median(ours_spp[i]);
    row.raw = column(ours_rmse[i], noise_mse);
    row.ldr = column(ours_ldr[i], noise_mse_ldr);
    row.denoised = column(denoised[i], noise_mse);
    row.denoised_ldr = column(denoised_ldr[i], noise_mse_ldr);
    row.cached = column(cached[i], noise_mse);
    row.cached_ldr = column(cached_ldr[i], noise_mse_ldr);
    row.reused = column(reused[i], noise_mse);
    row.reused_ldr = column(reused_ldr[i], noise_mse_ldr);
    result.rows.push_back(row);
  }
  return result;
}

}  // namespace tuneray
