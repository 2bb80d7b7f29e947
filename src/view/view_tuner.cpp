#include "view/view_tuner.h"

#include "tuning/bvh_space.h"
#include "tuning/tune_session.h"
#include "tuning/tuner_state.h"

namespace tuneray {

ViewTuner::ViewTuner(const Scene& scene, const RenderSettings& settings,
                     const ViewTuneOptions& options)
    : scene_(scene), scene_indicators_(compute_scene_indicators(scene)), options_(options) {
  // The session `tune --size WxH --spp 1 --max-bounces B --scheduler S` would be: the same key
  // and space, so the database is shared with it both ways.
  TuneOptions session;
  session.objective = options.objective;
  session.db_path = options.db_path;
  session.epsilon = options.epsilon;
  session.seed = options.seed;
  session.width = settings.width;
  session.height = settings.height;
  session.spp = 1;
  session.max_bounces = settings.max_bounces;
  session.wavefront = settings.quality.wavefront;
  key_ = tuneray::tuning_key(session);
  const tuner::Space space = make_tune_space(session, settings);
  tuner::TunerOptions tuner_options;
  tuner_options.epsilon = options.epsilon;
  tuner_options.seed = options.seed;
  tuner_options.search.max_iterations = session.iterations;
  tuner_options.db_path = options.db_path;
  tuner_options.tuning_key = key_;
  tuner_options.search_seeds = tuning_seeds(space, options.objective == Objective::kTotal);
  tuner_.emplace(space, make_indicator_schema(), tuner_options);
}

void ViewTuner::set_camera(const CameraDesc& camera) {
  state_ = to_tuner_state(compute_indicators(scene_indicators_, camera));
  frames_since_change_ = 0;
  status_.default_ms = status_.native_ms = status_.current_ms = 0;
}

bool ViewTuner::prepare(const AccelChoice& choice) {
  const GeometryView geometry{scene_.positions.data(), scene_.positions.size(),
                              scene_.triangles.data(), scene_.triangles.size()};
  frame_build_ms_ = 0;
  try {
    if (choice.is_native()) {
      if (native_built_ != choice.native_quality) {
        native_built_.reset();
        native_.set_options(choice.native_options());
        native_build_ms_ = frame_build_ms_ = native_.build(geometry).build_ms;
        native_built_ = choice.native_quality;
      }
    } else if (tuned_built_ != choice.bvh) {
      tuned_built_.reset();
      tuned_.set_config(choice.bvh);
      tuned_build_ms_ = frame_build_ms_ = tuned_.build(geometry).build_ms;
      tuned_built_ = choice.bvh;
    }
  } catch (const std::exception&) {  // BuildError, or a configuration the backend rejects
    return false;
  }
  return true;
}

const Accel& ViewTuner::accel_of(const AccelChoice& choice) const {
  if (choice.is_native()) return native_;
  return tuned_;
}

ViewTuner::Phase ViewTuner::phase() const {
  if (frames_since_change_ == kYardstickFrame) return Phase::kDefault;
  if (frames_since_change_ == kYardstickFrame + 1) return Phase::kNative;
  return Phase::kTuner;
}

const Accel& ViewTuner::next_accel() {
  pending_.reset();
  const AccelChoice default_choice = AccelChoice::tuned(BvhConfig{});
  const Phase now = phase();
  if (now == Phase::kDefault) {
    current_ = default_choice;
  } else if (now == Phase::kNative) {
    current_ = AccelChoice::native();
  } else {
    tuner::Config c = tuner_->suggest(state_);
    current_ = to_accel_choice(c);
    if (prepare(current_)) {
      pending_ = c;
      status_.mode = tuner_->mode() == tuner::TunerMode::kSearch ? "search" : "exploit";
      status_.config = current_.to_string();
      return accel_of(current_);
    }
    tuner_->report_failure(c);
    ++failed_builds_;
    current_ = default_choice;
  }
  // The default configuration and native Embree always build.
  prepare(current_);
  status_.mode = now == Phase::kNative ? "native" : now == Phase::kDefault ? "default" : "fallback";
  status_.config = current_.to_string();
  return accel_of(current_);
}

void ViewTuner::report(const FrameResult& frame) {
  if (!(frame.spp > 0) || !(frame.stats.render_ms > 0)) return;
  double cost_ms = frame.stats.render_ms / frame.spp;
  // Under `total` every frame of a real-time renderer rebuilds: the build counts in full.
  if (options_.objective == Objective::kTotal)
    cost_ms += current_.is_native() ? native_build_ms_ : tuned_build_ms_;
  const Phase now = phase();
  ++frames_since_change_;
  if (now == Phase::kDefault) {
    status_.default_ms = cost_ms;
  } else if (now == Phase::kNative) {
    status_.native_ms = cost_ms;
  } else {
    status_.current_ms = cost_ms;
    if (pending_)
      tuner_->report(*pending_, cost_ms / 1000.0,
                     {{"build_ms", frame_build_ms_}, {"render_ms", frame.stats.render_ms}});
  }
}

}  // namespace tuneray
