// tuneray_bluenoise_gen: optimises the blue-noise sampler's per-pixel keys and writes them as
// data/blue_noise_keys.u16, which the build embeds (data/README.md, docs/quality.md,
// "Blue-noise sampler").
//
// Every tile pixel starts with random keys (BlueNoiseTables::random_keys of its own index).
// What is optimised is which pixel gets which key set, per quadruple: a permutation. Each key
// set has an error vector (its errors on random half-plane integrands at 1 and 4 spp, each
// component normalised to unit variance over the key sets); the permutation minimises Heitz's
// energy E = sum over pixel pairs within a 7x7 toroidal window of
//   exp(-|p - p'|^2 / sigma_i^2 - |e - e'|^2 / sigma_s^2),
// i.e. close pixels are pushed to have different errors, by simulated annealing over random
// swaps (a swap keeps the set of keys, so every key is still used once per quadruple).
// Deterministic for a given --seed.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <numeric>
#include <vector>

#include "math/rng.h"
#include "render/blue_noise.h"
#include "render/blue_noise_error.h"

namespace tuneray {
namespace {

using namespace blue_noise;

constexpr int kRadius = 3;
constexpr float kSigmaI2 = 2.1f * 2.1f;

struct Options {
  std::string out = "data/blue_noise_keys.u16";
  uint64_t seed = 1;
  int integrands = 64;
  std::vector<uint32_t> spp_levels{1, 4};  // sample counts whose errors are optimised
  double swaps_per_pixel = 40;
  double temperature = 0.002;  // initial, relative to the mean pair energy; falls linearly to 0
};

class Annealer {
 public:
  Annealer(std::vector<float> errors, int dims) : e_(std::move(errors)), dims_(dims) {
    double sum = 0;
    Pcg32 rng(7, 1);
    for (int i = 0; i < 4096; ++i)
      sum += distance2(rng.next_u32() % kTilePixels, rng.next_u32() % kTilePixels);
    inv_sigma_s2_ = static_cast<float>(4096.0 / sum);
    for (int dy = -kRadius; dy <= kRadius; ++dy)
      for (int dx = -kRadius; dx <= kRadius; ++dx)
        if (dx || dy) offsets_.push_back({dx, dy, std::exp(-(dx * dx + dy * dy) / kSigmaI2)});
    perm_.resize(kTilePixels);
    std::iota(perm_.begin(), perm_.end(), 0);
  }

  double energy() const {
    double e = 0;
    for (int p = 0; p < kTilePixels; ++p) e += pixel_energy(p, perm_[p], -1);
    return e / 2;
  }

  void run(uint64_t swaps, double temperature, Pcg32& rng) {
    const double t0 = temperature * energy() / kTilePixels;
    for (uint64_t s = 0; s < swaps; ++s) {
      int p = static_cast<int>(rng.next_u32() % kTilePixels);
      int r = static_cast<int>(rng.next_u32() % kTilePixels);
      if (p == r) continue;
      double before = pixel_energy(p, perm_[p], r) + pixel_energy(r, perm_[r], p);
      double after = pixel_energy(p, perm_[r], r) + pixel_energy(r, perm_[p], p);
      double delta = after - before;
      double t = t0 * (1.0 - static_cast<double>(s) / swaps);
      if (delta < 0 || (t > 0 && rng.next_float() < std::exp(-delta / t)))
        std::swap(perm_[p], perm_[r]);
    }
  }

  const std::vector<uint16_t>& permutation() const { return perm_; }

 private:
  struct Offset {
    int dx, dy;
    float weight;
  };

  float distance2(uint32_t a, uint32_t b) const {
    const float* x = &e_[static_cast<size_t>(a) * dims_];
    const float* y = &e_[static_cast<size_t>(b) * dims_];
    float d = 0;
    for (int i = 0; i < dims_; ++i) d += (x[i] - y[i]) * (x[i] - y[i]);
    return d;
  }

  // Energy of pixel p holding key set `key` with its window; the pair with `skip` is left out
  // (a swap does not change it).
  double pixel_energy(int p, uint16_t key, int skip) const {
    int px = p % kTileSize, py = p / kTileSize;
    double e = 0;
    for (const Offset& o : offsets_) {
      int q =
          ((py + o.dy + kTileSize) % kTileSize) * kTileSize + (px + o.dx + kTileSize) % kTileSize;
      if (q == skip) continue;
      e += o.weight * std::exp(-distance2(key, perm_[q]) * inv_sigma_s2_);
    }
    return e;
  }

  std::vector<float> e_;
  int dims_;
  float inv_sigma_s2_ = 1;
  std::vector<Offset> offsets_;
  std::vector<uint16_t> perm_;
};

// Error vectors of every key set of quadruple q, components normalised to unit variance.
std::vector<float> error_vectors(const BlueNoiseTables& identity, int q,
                                 const std::vector<HalfPlane>& fs,
                                 const std::vector<uint32_t>& spp_levels, int* dims) {
  *dims = static_cast<int>(fs.size() * spp_levels.size());
  std::vector<float> e(static_cast<size_t>(kTilePixels) * *dims);
  for (int p = 0; p < kTilePixels; ++p) {
    const PixelKeys& keys = identity.keys(p % kTileSize, p / kTileSize);
    int c = 0;
    for (uint32_t spp : spp_levels)
      for (const HalfPlane& f : fs)
        e[static_cast<size_t>(p) * *dims + c++] = pixel_error(identity, keys, q, spp, f);
  }
  for (int c = 0; c < *dims; ++c) {
    double s2 = 0;
    for (int p = 0; p < kTilePixels; ++p) s2 += e[p * *dims + c] * e[p * *dims + c];
    float inv = s2 > 0 ? static_cast<float>(1.0 / std::sqrt(s2 / kTilePixels)) : 1.0f;
    for (int p = 0; p < kTilePixels; ++p) e[p * *dims + c] *= inv;
  }
  return e;
}

// Little-endian uint16, whatever the host: the build embeds the file byte for byte
// (cmake/embed_u16.cmake), so the table does not depend on the machine that generated it.
void write_table(const std::string& path, const std::vector<uint16_t>& origin) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot write " + path);
  for (uint16_t v : origin) {
    const char bytes[2] = {static_cast<char>(v & 0xff), static_cast<char>(v >> 8)};
    out.write(bytes, 2);
  }
  if (!out) throw std::runtime_error("error writing " + path);
}

int run(const Options& o) {
  if (o.spp_levels.empty()) throw std::invalid_argument("--spp-levels: give at least one count");
  for (uint32_t spp : o.spp_levels)
    if (spp < 1 || spp > kSamples)
      throw std::invalid_argument("--spp-levels: " + std::to_string(spp) + " not in 1..256");
  std::vector<uint16_t> identity(static_cast<size_t>(kQuadruples) * kTilePixels);
  for (size_t i = 0; i < identity.size(); ++i) identity[i] = static_cast<uint16_t>(i % kTilePixels);
  BlueNoiseTables tables(identity);
  std::vector<HalfPlane> fs = random_half_planes(o.seed, o.integrands);
  std::vector<uint16_t> origin;
  Pcg32 rng(mix_seed(o.seed), 11);
  for (int q = 0; q < kQuadruples; ++q) {
    int dims = 0;
    std::vector<float> errors = error_vectors(tables, q, fs, o.spp_levels, &dims);
    Annealer annealer(std::move(errors), dims);
    double before = annealer.energy();
    annealer.run(static_cast<uint64_t>(o.swaps_per_pixel * kTilePixels), o.temperature, rng);
    std::printf("quadruple %d: energy %.1f -> %.1f\n", q, before, annealer.energy());
    std::fflush(stdout);
    origin.insert(origin.end(), annealer.permutation().begin(), annealer.permutation().end());
  }
  // The test's measure (tests/render/test_blue_noise.cpp), on integrands not optimised for.
  BlueNoiseTables optimised(origin);
  std::vector<HalfPlane> held_out = random_half_planes(12345, 4);
  for (uint32_t spp : {1u, 4u, 16u}) {
    double share_opt = 0, share_rand = 0;
    for (int q = 0; q < kQuadruples; ++q)
      for (const HalfPlane& f : held_out) {
        share_opt += low_frequency_share(error_image(optimised, q, spp, f));
        share_rand += low_frequency_share(error_image(tables, q, spp, f));
      }
    std::printf("held-out integrands, %2u spp: low-frequency share optimised / random = %.3f\n",
                spp, share_opt / share_rand);
  }
  if (o.out.empty()) return 0;
  write_table(o.out, origin);
  std::printf("wrote %s\n", o.out.c_str());
  return 0;
}

}  // namespace
}  // namespace tuneray

int main(int argc, char** argv) {
  tuneray::Options o;
  CLI::App app{"Optimise the blue-noise sampler's keys and write them as data/blue_noise_keys.u16"};
  app.add_option("--out", o.out, "Output file (little-endian uint16)")->capture_default_str();
  app.add_option("--seed", o.seed, "Seed of integrands and annealing")->capture_default_str();
  app.add_option("--integrands", o.integrands, "Half-plane test integrands")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  app.add_option("--swaps-per-pixel", o.swaps_per_pixel, "Annealing budget")
      ->check(CLI::Range(0.0, 1e4))
      ->capture_default_str();
  app.add_option("--temperature", o.temperature, "Initial temperature (relative)")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  app.add_option("--spp-levels", o.spp_levels, "Sample counts whose errors are optimised")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    return tuneray::run(o);
  } catch (const std::exception& e) {
    std::cerr << "tuneray_bluenoise_gen: " << e.what() << "\n";
    return 1;
  }
}
