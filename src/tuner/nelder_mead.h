// Stochastic Nelder-Mead simplex search in the normalised space, driven ask/tell style.
//
// The search never stores costs itself: it reads them through a Lookup (configuration -> every
// cost recorded for it in the current state) and asks for a measurement whenever a point it needs
// has fewer repeats than required. So a configuration already measured (for example two points
// that round to the same configuration) is never measured again unless more repeats are wanted
// on purpose, and the search state stays small enough to be saved after every report.
//
// Choices (all in NelderMeadOptions, defaults in brackets):
// - First simplex: the start point (the default configuration, or a warm start) plus n points
//   drawn by Latin Hypercube sampling in a box of half-width `initial_radius` [0.25] around it
//   (shifted to stay inside [0,1]^n), so the n edges point in well spread directions. A discrete
//   coordinate's box is at least one value wide on each side. Seed points given by the caller
//   (configurations known to be good in general) replace the first LHS points, so the first
//   comparison already includes them and the search can only end at least as good as the best
//   of them (up to noise).
// - Moves: the classic reflection [1], expansion [2], outside/inside contraction [0.5] and
//   shrink [0.5]; every new point is clamped to [0,1]^n and repaired to satisfy the constraints
//   (Space::feasible), so a move never leaves the feasible set.
// - Noise: points are compared by the median of their repeats, which ignores a minority of
//   outliers (e.g. a measurement hit by a context switch). Every vertex gets `r` repeats and the
//   incumbent (best vertex) one more, so a single lucky measurement cannot keep a point on top.
//   `r` starts at `min_repeats` [1] and grows by one each time the simplex size halves relative
//   to its first size, up to `max_repeats` [3]: late in the search the points are close and
//   their differences are comparable to the noise, early on they are not.
//   A failed measurement (cost = +infinity) counts as fully measured: failures are
//   deterministic, re-running them would waste time.
// - Degenerate simplex: when an edge (from the incumbent), after Gram-Schmidt against the
//   previous edges, is shorter than `degeneracy_tolerance` [1e-3] times the longest edge, the
//   simplex has lost a dimension (rounding and constraint repair cause this). It is rebuilt
//   around the incumbent with the current size (at least 4 x_tolerance, at most initial_radius),
//   at most `max_restarts` [6] times in all (with the restarts below); after that the search
//   stops, not converged.
// - Budget: `max_iterations` [80] iterations; one iteration is one reflection step with its
//   expansion, contraction or shrink, counted only when it (or the re-measurements before it)
//   asked for a measurement: on plateaus of discrete parameters many moves land on recorded
//   configurations and cost nothing. Free iterations are capped at 10 x max_iterations.
// - Convergence: the simplex is small: its size (largest distance from the incumbent to another
//   vertex, in the normalised space) is below `x_tolerance` [1e-3], or all vertices round to
//   the same configuration. Noise can make a simplex collapse around a point that only looked
//   best, so a small simplex first restarts around the incumbent (box half-width
//   initial_radius / 2^restarts); the search has converged when two restarts in a row did not
//   improve the incumbent's median (or max_restarts is reached). A value
//   tolerance is not used because with noisy costs close values do not mean convergence.
// - Conditional parameters: a point's coordinates of inactive parameters mean nothing (they
//   decode to the default), yet a restart's box is drawn around them. So the search keeps the
//   best points it has compared (up to 2(n+1), by their current medians), and a restart around an
//   incumbent with inactive parameters takes their coordinates from the best remembered point in
//   which some of them are active, with a box of at least `initial_radius` along them (nothing
//   has been narrowed down there). Without it a search whose incumbent moved into a branch that
//   switches most parameters off (e.g. another backend with none of them) restarted around
//   coordinates it never measured (the start point's) in ever smaller boxes and declared
//   convergence there after two stale restarts. The incumbent's configuration is unchanged by
//   this; only where a restart looks across the condition is.
#pragma once

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tuner/config.h"
#include "tuner/rng.h"
#include "tuner/space.h"

namespace tuneray::tuner {

struct NelderMeadOptions {
  int max_iterations = 80;
  double initial_radius = 0.25;
  double reflection = 1.0;
  double expansion = 2.0;
  double contraction = 0.5;
  double shrink = 0.5;
  int min_repeats = 1;
  int max_repeats = 3;
  double x_tolerance = 1e-3;
  double degeneracy_tolerance = 1e-3;
  int max_restarts = 6;
};

class NelderMead {
 public:
  // Every cost recorded for a configuration in the current state, or nullptr if none.
  using Lookup = std::function<const std::vector<double>*(const Config&)>;

  // `start` and `seeds` are normalised points; `space` must outlive the search. At most n seeds
  // are used (n = dimensions); seeds equal to the start point or to each other are skipped.
  NelderMead(const Space& space, const NelderMeadOptions& options, std::vector<double> start,
             uint64_t seed, std::vector<std::vector<double>> seeds = {});

  // The configuration to measure next, or nullopt once the search has finished. Calling it
  // again without a new measurement returns the same configuration.
  std::optional<Config> next(const Lookup& lookup);

  bool finished() const { return phase_ == Phase::kDone; }
  bool converged() const { return converged_; }
  // Iterations that asked for at least one measurement (what the budget counts).
  int iterations() const { return charged_iterations_; }
  // All iterations, including those whose points were all already measured.
  int total_iterations() const { return iterations_; }
  int restarts() const { return restarts_; }
  int repeats() const { return repeats_; }
  double size() const;  // current simplex size in the normalised space
  // Best vertex as of the last comparison (the start point before any).
  Config incumbent() const { return space_->decode(vertices_.front()); }
  const std::vector<std::vector<double>>& vertices() const { return vertices_; }

  // Text form with exact doubles; deserialise(serialise()) continues identically.
  std::string serialise() const;
  static NelderMead deserialise(const Space& space, const NelderMeadOptions& options,
                                std::string_view text);

 private:
  enum class Phase { kEvaluate = 0, kReflect = 1, kExpand = 2, kContract = 3, kDone = 4 };

  NelderMead(const Space& space, const NelderMeadOptions& options);
  std::optional<Config> advance(const Lookup& lookup);
  // `wide` lists coordinates whose box keeps at least initial_radius (those a restart took from
  // another branch's best point: nothing there has been narrowed down yet).
  void build_simplex(const std::vector<double>& centre, double radius,
                     std::vector<std::vector<double>> seeds = {},
                     const std::vector<size_t>& wide = {});
  bool needs_measurement(const Lookup& lookup, const Config& config, int repeats) const;
  double value(const Lookup& lookup, const std::vector<double>& point) const;
  void sort_vertices(const Lookup& lookup);
  bool collapsed() const;
  bool degenerate() const;
  // Adds the vertices' points to archive_ (conditional spaces only), keeping the best.
  void remember_vertices(const Lookup& lookup);
  // The incumbent's point with its inactive coordinates taken from the best archived point in
  // which some of them are active (see the header comment); `across` gets those coordinates
  // (empty when none were taken).
  std::vector<double> restart_centre(const Lookup& lookup, std::vector<size_t>& across) const;
  int repeats_for(double size) const;
  std::vector<double> along(const std::vector<double>& from, const std::vector<double>& to,
                            double t) const;  // feasible from + t (to - from)
  void finish(bool converged);

  const Space* space_;
  NelderMeadOptions options_;
  Rng rng_;
  Phase phase_ = Phase::kEvaluate;
  std::vector<std::vector<double>> vertices_;
  std::vector<double> centroid_;
  std::vector<double> reflected_;
  std::vector<double> trial_;
  bool outside_contraction_ = false;
  bool converged_ = false;
  int iterations_ = 0;
  int charged_iterations_ = 0;  // iterations that asked for at least one measurement
  int64_t requests_ = 0;
  int64_t requests_at_iteration_start_ = 0;
  int restarts_ = 0;
  int repeats_ = 1;
  double initial_size_ = 0.0;
  int stale_restarts_ = 0;
  double restart_cost_ = std::numeric_limits<double>::infinity();
  std::vector<std::vector<double>> archive_;  // best points compared so far (conditional spaces)
};

// Median of recorded costs; +infinity if any is a failure or the list is empty.
double robust_cost(const std::vector<double>& costs);

}  // namespace tuneray::tuner
