#include "tuner/nelder_mead.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "tuner/latin_hypercube.h"
#include "tuner/token_io.h"

namespace tuneray::tuner {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Iterations that measure nothing (every point already recorded) are free, but bounded.
constexpr int kFreeIterationFactor = 10;
// Consecutive restarts from a small simplex that did not improve the incumbent before the
// search is declared converged: one can fail by bad luck with noisy costs, two rarely do.
constexpr int kStaleRestartLimit = 2;
// Points remembered for restarts in a conditional space, per simplex vertex.
constexpr size_t kArchivePerVertex = 2;

bool has_conditions(const Space& space) {
  for (size_t i = 0; i < space.size(); ++i) {
    if (space.param(i).active_when) return true;
  }
  return false;
}

double distance(const std::vector<double>& a, const std::vector<double>& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) sum += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(sum);
}

}  // namespace

double robust_cost(const std::vector<double>& costs) {
  if (costs.empty()) return kInfinity;
  std::vector<double> sorted = costs;
  std::sort(sorted.begin(), sorted.end());
  if (std::isinf(sorted.back())) return kInfinity;
  const size_t mid = sorted.size() / 2;
  return sorted.size() % 2 ? sorted[mid] : 0.5 * (sorted[mid - 1] + sorted[mid]);
}

NelderMead::NelderMead(const Space& space, const NelderMeadOptions& options)
    : space_(&space), options_(options) {}

NelderMead::NelderMead(const Space& space, const NelderMeadOptions& options,
                       std::vector<double> start, uint64_t seed,
                       std::vector<std::vector<double>> seeds)
    : space_(&space), options_(options), rng_(seed) {
  if (start.size() != space.size()) throw std::invalid_argument("NelderMead: bad start point");
  if (options.max_repeats < options.min_repeats || options.min_repeats < 1) {
    throw std::invalid_argument("NelderMead: need 1 <= min_repeats <= max_repeats");
  }
  repeats_ = options.min_repeats;
  space.feasible(start);
  for (const auto& point : seeds) {
    if (point.size() != space.size()) throw std::invalid_argument("NelderMead: bad seed point");
  }
  build_simplex(start, options.initial_radius, std::move(seeds));
  initial_size_ = size();
  if (space.size() == 0) finish(true);
}

void NelderMead::build_simplex(const std::vector<double>& centre, double radius,
                               std::vector<std::vector<double>> seeds,
                               const std::vector<size_t>& wide) {
  const size_t dims = centre.size();
  vertices_.assign(1, centre);
  // Seeds first (as configurations: two points that round to one configuration are one seed).
  std::vector<Config> taken = {space_->decode(centre)};
  for (auto& point : seeds) {
    if (vertices_.size() > dims) break;
    space_->feasible(point);
    Config config = space_->decode(point);
    if (std::find(taken.begin(), taken.end(), config) != taken.end()) continue;
    taken.push_back(std::move(config));
    vertices_.push_back(std::move(point));
  }
  const size_t lhs_points = dims + 1 - vertices_.size();
  for (auto& unit : latin_hypercube(lhs_points, dims, rng_)) {
    for (size_t d = 0; d < dims; ++d) {
      // A discrete coordinate gets at least one cell on each side, so that a small simplex
      // still reaches the neighbouring values instead of sitting on one plateau.
      const size_t cells = space_->param(d).cardinality();
      const double cell = cells > 0 ? 1.0 / static_cast<double>(cells) : 0.0;
      const bool is_wide = std::find(wide.begin(), wide.end(), d) != wide.end();
      const double r = is_wide ? std::max(radius, options_.initial_radius) : radius;
      const double width = std::min(1.0, 2.0 * std::max(r, cell));
      const double lo = std::clamp(centre[d] - 0.5 * width, 0.0, 1.0 - width);
      unit[d] = lo + width * unit[d];
    }
    space_->feasible(unit);
    vertices_.push_back(std::move(unit));
  }
}

void NelderMead::remember_vertices(const Lookup& lookup) {
  if (!has_conditions(*space_)) return;
  std::vector<Config> known;
  known.reserve(archive_.size() + vertices_.size());
  for (const auto& point : archive_) known.push_back(space_->decode(point));
  for (const auto& vertex : vertices_) {
    Config config = space_->decode(vertex);
    if (std::find(known.begin(), known.end(), config) != known.end()) continue;
    known.push_back(std::move(config));
    archive_.push_back(vertex);
  }
  const size_t capacity = kArchivePerVertex * vertices_.size();
  if (archive_.size() <= capacity) return;
  std::vector<std::pair<double, size_t>> order(archive_.size());
  for (size_t i = 0; i < archive_.size(); ++i) order[i] = {value(lookup, archive_[i]), i};
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::vector<double>> kept;
  kept.reserve(capacity);
  for (size_t i = 0; i < capacity; ++i) kept.push_back(std::move(archive_[order[i].second]));
  archive_ = std::move(kept);
}

std::vector<double> NelderMead::restart_centre(const Lookup& lookup,
                                               std::vector<size_t>& across) const {
  across.clear();
  std::vector<double> centre = vertices_[0];
  const Config incumbent = space_->decode(centre);
  std::vector<size_t> inactive;
  for (size_t d = 0; d < centre.size(); ++d) {
    if (!space_->is_active(incumbent, d)) inactive.push_back(d);
  }
  if (inactive.empty()) return centre;
  const std::vector<double>* donor = nullptr;
  double donor_cost = kInfinity;
  for (const auto& point : archive_) {
    const Config config = space_->decode(point);
    const bool activates = std::any_of(inactive.begin(), inactive.end(),
                                       [&](size_t d) { return space_->is_active(config, d); });
    if (!activates) continue;
    const double cost = value(lookup, point);
    if (cost < donor_cost) {
      donor_cost = cost;
      donor = &point;
    }
  }
  // Inactive coordinates do not change what the centre decodes to, only where the restart's
  // box reaches across the condition.
  if (donor != nullptr) {
    for (size_t d : inactive) centre[d] = (*donor)[d];
    across = std::move(inactive);
  }
  return centre;
}

double NelderMead::size() const {
  double largest = 0.0;
  for (size_t i = 1; i < vertices_.size(); ++i) {
    largest = std::max(largest, distance(vertices_[i], vertices_[0]));
  }
  return largest;
}

bool NelderMead::needs_measurement(const Lookup& lookup, const Config& config, int repeats) const {
  const std::vector<double>* costs = lookup(config);
  if (costs == nullptr || costs->empty()) return true;
  if (std::any_of(costs->begin(), costs->end(), [](double c) { return std::isinf(c); })) {
    return false;
  }
  return static_cast<int>(costs->size()) < repeats;
}

double NelderMead::value(const Lookup& lookup, const std::vector<double>& point) const {
  const std::vector<double>* costs = lookup(space_->decode(point));
  return costs ? robust_cost(*costs) : kInfinity;
}

void NelderMead::sort_vertices(const Lookup& lookup) {
  std::vector<std::pair<double, size_t>> order(vertices_.size());
  for (size_t i = 0; i < vertices_.size(); ++i) order[i] = {value(lookup, vertices_[i]), i};
  // Stable on ties so that the result does not depend on the sort implementation.
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::vector<double>> sorted;
  sorted.reserve(vertices_.size());
  for (const auto& entry : order) sorted.push_back(std::move(vertices_[entry.second]));
  vertices_ = std::move(sorted);
}

bool NelderMead::collapsed() const {
  const Config first = space_->decode(vertices_[0]);
  for (size_t i = 1; i < vertices_.size(); ++i) {
    if (!(space_->decode(vertices_[i]) == first)) return false;
  }
  return true;
}

bool NelderMead::degenerate() const {
  const double scale = size();
  if (scale == 0.0) return true;
  std::vector<std::vector<double>> basis;
  for (size_t i = 1; i < vertices_.size(); ++i) {
    std::vector<double> edge(vertices_[i].size());
    for (size_t d = 0; d < edge.size(); ++d) edge[d] = vertices_[i][d] - vertices_[0][d];
    for (const auto& b : basis) {
      const double projection = std::inner_product(edge.begin(), edge.end(), b.begin(), 0.0);
      for (size_t d = 0; d < edge.size(); ++d) edge[d] -= projection * b[d];
    }
    const double norm = std::sqrt(std::inner_product(edge.begin(), edge.end(), edge.begin(), 0.0));
    if (norm < options_.degeneracy_tolerance * scale) return true;
    for (double& e : edge) e /= norm;
    basis.push_back(std::move(edge));
  }
  return false;
}

int NelderMead::repeats_for(double size) const {
  if (size <= 0.0 || initial_size_ <= 0.0) return options_.max_repeats;
  const double halvings = std::floor(std::log2(initial_size_ / size));
  const double wanted = options_.min_repeats + std::max(0.0, halvings);
  return static_cast<int>(std::min<double>(options_.max_repeats, wanted));
}

std::vector<double> NelderMead::along(const std::vector<double>& from,
                                      const std::vector<double>& to, double t) const {
  std::vector<double> point(from.size());
  for (size_t d = 0; d < point.size(); ++d) point[d] = from[d] + t * (to[d] - from[d]);
  space_->feasible(point);
  return point;
}

void NelderMead::finish(bool converged) {
  phase_ = Phase::kDone;
  converged_ = converged;
}

std::optional<Config> NelderMead::next(const Lookup& lookup) {
  std::optional<Config> request = advance(lookup);
  if (request) ++requests_;
  return request;
}

std::optional<Config> NelderMead::advance(const Lookup& lookup) {
  // Each pass either asks for a measurement, finishes, or moves to another phase; the bound
  // only guards against a bug turning into a hang.
  for (int pass = 0; pass < 100000; ++pass) {
    switch (phase_) {
      case Phase::kDone:
        return std::nullopt;

      case Phase::kEvaluate: {
        for (const auto& vertex : vertices_) {
          Config config = space_->decode(vertex);
          if (needs_measurement(lookup, config, repeats_)) return config;
        }
        sort_vertices(lookup);
        remember_vertices(lookup);
        Config incumbent = space_->decode(vertices_[0]);
        if (needs_measurement(lookup, incumbent, repeats_ + 1)) return incumbent;

        const double current_size = size();
        const bool small = current_size <= options_.x_tolerance || collapsed();
        if (requests_ != requests_at_iteration_start_) {
          ++charged_iterations_;
          requests_at_iteration_start_ = requests_;
        }
        if (charged_iterations_ >= options_.max_iterations ||
            iterations_ >= kFreeIterationFactor * options_.max_iterations) {
          finish(small);
          return std::nullopt;
        }
        if (small) {
          // Noise makes a simplex shrink around a point that only looked best; restart around
          // the incumbent with a smaller box while restarts keep improving it.
          const double incumbent_cost = value(lookup, vertices_[0]);
          stale_restarts_ = incumbent_cost < restart_cost_ ? 0 : stale_restarts_ + 1;
          if (restarts_ >= options_.max_restarts || stale_restarts_ >= kStaleRestartLimit) {
            finish(true);
            return std::nullopt;
          }
          ++restarts_;
          restart_cost_ = incumbent_cost;
          std::vector<size_t> across;
          const std::vector<double> centre = restart_centre(lookup, across);
          build_simplex(centre, options_.initial_radius * std::pow(0.5, restarts_), {}, across);
          continue;
        }
        if (degenerate()) {
          if (restarts_ >= options_.max_restarts) {
            finish(false);
            return std::nullopt;
          }
          ++restarts_;
          const double radius =
              std::clamp(current_size, 4.0 * options_.x_tolerance, options_.initial_radius);
          std::vector<size_t> across;
          const std::vector<double> centre = restart_centre(lookup, across);
          build_simplex(centre, radius, {}, across);
          continue;
        }
        const int wanted = repeats_for(current_size);
        if (wanted > repeats_) {
          repeats_ = wanted;
          continue;
        }
        const size_t n = vertices_.size() - 1;
        centroid_.assign(vertices_[0].size(), 0.0);
        for (size_t i = 0; i < n; ++i) {
          for (size_t d = 0; d < centroid_.size(); ++d) centroid_[d] += vertices_[i][d] / n;
        }
        reflected_ = along(centroid_, vertices_.back(), -options_.reflection);
        ++iterations_;
        phase_ = Phase::kReflect;
        continue;
      }

      case Phase::kReflect: {
        Config config = space_->decode(reflected_);
        if (needs_measurement(lookup, config, repeats_)) return config;
        const double f_reflected = value(lookup, reflected_);
        const double f_best = value(lookup, vertices_.front());
        const double f_second_worst = value(lookup, vertices_[vertices_.size() - 2]);
        const double f_worst = value(lookup, vertices_.back());
        if (f_reflected < f_best) {
          trial_ = along(centroid_, reflected_, options_.expansion);
          phase_ = Phase::kExpand;
        } else if (f_reflected < f_second_worst) {
          vertices_.back() = reflected_;
          phase_ = Phase::kEvaluate;
        } else {
          outside_contraction_ = f_reflected < f_worst;
          trial_ = along(centroid_, outside_contraction_ ? reflected_ : vertices_.back(),
                         options_.contraction);
          phase_ = Phase::kContract;
        }
        continue;
      }

      case Phase::kExpand: {
        Config config = space_->decode(trial_);
        if (needs_measurement(lookup, config, repeats_)) return config;
        const bool expanded_better = value(lookup, trial_) < value(lookup, reflected_);
        vertices_.back() = expanded_better ? trial_ : reflected_;
        phase_ = Phase::kEvaluate;
        continue;
      }

      case Phase::kContract: {
        Config config = space_->decode(trial_);
        if (needs_measurement(lookup, config, repeats_)) return config;
        const double f_trial = value(lookup, trial_);
        const bool accepted = outside_contraction_ ? f_trial <= value(lookup, reflected_)
                                                   : f_trial < value(lookup, vertices_.back());
        if (accepted) {
          vertices_.back() = trial_;
        } else {
          for (size_t i = 1; i < vertices_.size(); ++i) {
            vertices_[i] = along(vertices_[0], vertices_[i], options_.shrink);
          }
        }
        phase_ = Phase::kEvaluate;
        continue;
      }
    }
  }
  throw std::logic_error("NelderMead::next made no progress");
}

std::string NelderMead::serialise() const {
  TokenWriter out;
  out.put_word("nm2").put(static_cast<int>(phase_)).put(outside_contraction_).put(converged_);
  out.put(iterations_).put(charged_iterations_).put(requests_).put(requests_at_iteration_start_);
  out.put(restarts_).put(repeats_).put(initial_size_).put(restart_cost_).put(stale_restarts_);
  out.put(rng_);
  out.put(centroid_).put(reflected_).put(trial_);
  out.put(static_cast<int64_t>(vertices_.size()));
  for (const auto& v : vertices_) out.put(v);
  out.put(static_cast<int64_t>(archive_.size()));
  for (const auto& point : archive_) out.put(point);
  return out.str();
}

NelderMead NelderMead::deserialise(const Space& space, const NelderMeadOptions& options,
                                   std::string_view text) {
  TokenReader in(text);
  // nm1: the states saved before restarts remembered points (read with an empty archive).
  const std::string version = in.get_word();
  if (version != "nm1" && version != "nm2")
    throw std::runtime_error("not a Nelder-Mead search state");
  NelderMead search(space, options);
  const int64_t phase = in.get_int();
  if (phase < 0 || phase > static_cast<int>(Phase::kDone)) {
    throw std::runtime_error("bad phase in Nelder-Mead search state");
  }
  search.phase_ = static_cast<Phase>(phase);
  search.outside_contraction_ = in.get_bool();
  search.converged_ = in.get_bool();
  search.iterations_ = static_cast<int>(in.get_int());
  search.charged_iterations_ = static_cast<int>(in.get_int());
  search.requests_ = in.get_int();
  search.requests_at_iteration_start_ = in.get_int();
  search.restarts_ = static_cast<int>(in.get_int());
  search.repeats_ = static_cast<int>(in.get_int());
  search.initial_size_ = in.get_double();
  search.restart_cost_ = in.get_double();
  search.stale_restarts_ = static_cast<int>(in.get_int());
  in.get(search.rng_);
  search.centroid_ = in.get_doubles();
  search.reflected_ = in.get_doubles();
  search.trial_ = in.get_doubles();
  const int64_t count = in.get_int();
  if (count != static_cast<int64_t>(space.size()) + 1) {
    throw std::runtime_error("Nelder-Mead search state does not match the space");
  }
  for (int64_t i = 0; i < count; ++i) {
    search.vertices_.push_back(in.get_doubles());
    if (search.vertices_.back().size() != space.size()) {
      throw std::runtime_error("Nelder-Mead search state does not match the space");
    }
  }
  if (version == "nm2") {
    const int64_t remembered = in.get_int();
    if (remembered < 0 ||
        remembered > static_cast<int64_t>(kArchivePerVertex * search.vertices_.size())) {
      throw std::runtime_error("bad archive size in Nelder-Mead search state");
    }
    for (int64_t i = 0; i < remembered; ++i) {
      search.archive_.push_back(in.get_doubles());
      if (search.archive_.back().size() != space.size()) {
        throw std::runtime_error("Nelder-Mead search state does not match the space");
      }
    }
  }
  return search;
}

}  // namespace tuneray::tuner
