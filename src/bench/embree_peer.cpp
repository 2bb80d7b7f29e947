#include "bench/embree_peer.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "image/atomic_file.h"

namespace tuneray {

namespace {

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

struct CommandResult {
  int status = -1;
  std::string output;  // stdout and stderr
};

CommandResult run_command(const std::string& cmd) {
  CommandResult r;
  FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + cmd);
  std::array<char, 512> buf;
  while (fgets(buf.data(), buf.size(), pipe)) r.output += buf.data();
  r.status = pclose(pipe);
  return r;
}

std::string base_command(const EmbreePeer& p, int spp) {
  return fmt::format("{} -c {} --size {} {} --spp {} --max-path-length {}", shell_quote(p.binary),
                     shell_quote(p.scene), p.width, p.height, spp, p.max_path_length);
}

// The benchmark lines look like "BENCHMARK_RENDER_AVG 1.0220"; 0 when absent.
double read_benchmark_value(const std::string& output, const std::string& key) {
  size_t at = output.find(key + " ");
  if (at == std::string::npos) return 0.0;
  double v = std::atof(output.c_str() + at + key.size() + 1);
  return std::isfinite(v) ? v : 0.0;
}

std::string excerpt(const std::string& output) {
  return output.size() > 400 ? output.substr(0, 400) + "..." : output;
}

}  // namespace

std::string embree_peer_missing(const EmbreePeer& p) {
  if (!std::filesystem::exists(p.binary))
    return "Embree's pathtracer " + p.binary + " is not installed (package embree-tools)";
  if (!std::filesystem::exists(p.scene))
    return "Embree's scene " + p.scene + " is not installed (package embree-tools)";
  return "";
}

EmbreePeerTiming embree_peer_benchmark(const EmbreePeer& p, int spp, int frames) {
  std::string cmd = base_command(p, spp) + fmt::format(" --benchmark 1 {} --legacy", frames);
  CommandResult r = run_command(cmd);
  double fps = read_benchmark_value(r.output, "BENCHMARK_RENDER_AVG");
  if (r.status != 0 || !(fps > 0))
    throw std::runtime_error("Embree's pathtracer failed (" + cmd + "): " + excerpt(r.output));
  return {1000.0 / fps, read_benchmark_value(r.output, "BENCHMARK_RENDER_MRAYPS_AVG")};
}

void embree_peer_render(const EmbreePeer& p, int spp, const std::string& path) {
  if (std::filesystem::path(path).extension() != ".pfm")
    throw std::invalid_argument("the pathtracer's image must be a .pfm file: " + path);
  replace_file(path, [&](const std::string& temporary) {
    // The pathtracer picks its format by the extension: the temporary name must end in .pfm.
    std::string target = temporary + ".pfm";
    std::string cmd = base_command(p, spp) + " -o " + shell_quote(target);
    CommandResult r = run_command(cmd);
    std::error_code ec;
    if (r.status != 0 || !std::filesystem::exists(target, ec)) {
      std::filesystem::remove(target, ec);
      throw std::runtime_error("Embree's pathtracer failed (" + cmd + "): " + excerpt(r.output));
    }
    std::filesystem::rename(target, temporary);
  });
}

Image embree_output_transform(const Image& linear) {
  Image out(linear.width(), linear.height());
  auto quantise = [](float v) {
    float c = std::clamp(v, 0.0f, 1.0f);  // NaN stays NaN through clamp: map it to 0
    if (!(c == c)) c = 0;
    return std::floor(255.01f * c) / 255.0f;
  };
  for (size_t i = 0; i < linear.pixel_count(); ++i) {
    const Color& c = linear.data()[i];
    out.data()[i] = Color(quantise(c.x), quantise(c.y), quantise(c.z));
  }
  return out;
}

}  // namespace tuneray
