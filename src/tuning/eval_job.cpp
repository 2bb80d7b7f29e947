#include "tuning/eval_job.h"

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "tuner/hybrid_tuner.h"
#include "tuning/tuner_state.h"

namespace tuneray {

namespace {

using nlohmann::json;

json frames_json(const std::vector<EvalFrame>& frames) {
  json a = json::array();
  for (const EvalFrame& f : frames)
    a.push_back({{"config", f.config},
                 {"ok", f.ok},
                 {"cost_s", f.cost_s},
                 {"build_ms", f.build_ms},
                 {"render_ms", f.render_ms},
                 {"yardstick_ms", f.yardstick_ms}});
  return a;
}

std::vector<EvalFrame> parse_frames(const json& a) {
  std::vector<EvalFrame> frames;
  for (const json& f : a.at("frames"))
    frames.push_back({f.at("config").get<std::string>(), f.at("ok").get<bool>(),
                      f.at("cost_s").get<double>(), f.at("build_ms").get<double>(),
                      f.at("render_ms").get<double>(), f.at("yardstick_ms").get<double>()});
  return frames;
}

template <typename Parse>
auto parse_or_throw(const std::string& text, const char* what, Parse parse) {
  try {
    return parse(json::parse(text));
  } catch (const json::exception& e) {
    throw std::runtime_error(std::string("malformed ") + what + " message: " + e.what());
  }
}

}  // namespace

std::string to_json(const EvalJob& job) {
  return json{{"scene", job.scene},
              {"objective", job.objective},
              {"camera", job.camera},
              {"search", job.search},
              {"done_hardware", job.done_hardware},
              {"frames", frames_json(job.done)},
              {"compare", job.compare}}
      .dump();
}

std::string to_json(const EvalJobResult& r) {
  return json{{"scene", r.scene},
              {"objective", r.objective},
              {"camera", r.camera},
              {"hardware", r.hardware},
              {"frames", frames_json(r.frames)},
              {"comparison", r.comparison ? json::parse(to_json(*r.comparison)) : json()}}
      .dump();
}

EvalJob parse_eval_job(const std::string& text) {
  return parse_or_throw(text, "job", [](const json& j) {
    EvalJob job;
    job.scene = j.at("scene").get<int>();
    job.objective = j.at("objective").get<int>();
    job.camera = j.at("camera").get<int>();
    job.search = j.at("search").get<bool>();
    job.done_hardware = j.at("done_hardware").get<std::string>();
    job.done = parse_frames(j);
    job.compare = j.at("compare").get<std::vector<std::string>>();
    return job;
  });
}

EvalJobResult parse_eval_job_result(const std::string& text) {
  return parse_or_throw(text, "result", [](const json& j) {
    EvalJobResult r;
    r.scene = j.at("scene").get<int>();
    r.objective = j.at("objective").get<int>();
    r.camera = j.at("camera").get<int>();
    r.hardware = j.at("hardware").get<std::string>();
    r.frames = parse_frames(j);
    if (const json& c = j.at("comparison"); !c.is_null())
      r.comparison = parse_eval_comparison(c.dump());
    return r;
  });
}

EvalJobResult run_eval_job(const EvalProfile& p, const EvalScene& scene, EvalCostSource& costs,
                           const EvalJob& job, const std::string& hardware) {
  if (job.objective < 0 || job.objective >= static_cast<int>(p.objectives.size()) ||
      job.camera < 0 || job.camera >= static_cast<int>(scene.states.size()))
    throw std::runtime_error("job out of the profile's range");
  const Objective objective = p.objectives[static_cast<size_t>(job.objective)];
  EvalJobResult r;
  r.scene = job.scene;
  r.objective = job.objective;
  r.camera = job.camera;
  r.hardware = hardware;
  if (job.search) {
    const std::string run_key = eval_run_key(p, scene.name, objective);
    tuner::HybridTuner tuner(eval_space(p), make_indicator_schema(),
                             eval_tuner_options(p, objective, run_key, job.camera));
    const tuner::State& state = scene.states[static_cast<size_t>(job.camera)];
    if (job.done_hardware == hardware)
      for (const EvalFrame& frame : job.done) {
        replay_search_frame(tuner, state, frame);
        r.frames.push_back(frame);
      }
    while (r.frames.size() < static_cast<size_t>(p.iterations))
      r.frames.push_back(measure_search_frame(p, static_cast<int>(r.frames.size()), tuner, state,
                                              costs, objective, job.camera));
  }
  if (!job.compare.empty())
    r.comparison =
        measure_comparison(costs, objective, job.camera, job.compare, comparison_options(p));
  return r;
}

}  // namespace tuneray
