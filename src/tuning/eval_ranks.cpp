#include "tuning/eval_ranks.h"

#include <fmt/core.h>

#include <map>
#include <memory>
#include <stdexcept>

#include "tuner/hybrid_tuner.h"
#include "tuning/comparison_log.h"
#include "tuning/eval_scene.h"
#include "tuning/eval_search.h"
#include "tuning/tuner_state.h"

namespace tuneray {

namespace {

// A plan is complete after two rounds (searches, then the comparisons, which need every
// camera's search for the predictions); a third that still finds work means a rank delivers
// something else than what was asked.
constexpr int kMaxRounds = 4;

void check_indices(const EvalProfile& p, int scene, int objective, int camera) {
  if (scene < 0 || scene >= static_cast<int>(p.scenes.size()) || objective < 0 ||
      objective >= static_cast<int>(p.objectives.size()) || camera < 0 || camera >= p.cameras)
    throw std::runtime_error(
        fmt::format("job ({}, {}, {}) is not in the profile", scene, objective, camera));
}

// Stores one job's result as a single-rank run would have stored it while measuring: each
// search frame replayed into the tuner of the database (one transaction per frame), the
// comparison appended whole to the comparison log.
void store_result(const EvalProfile& p, const EvalPaths& paths, const EvalScene& scene,
                  const EvalJobResult& r) {
  const Objective objective = p.objectives[static_cast<size_t>(r.objective)];
  const std::string run_key = eval_run_key(p, scene.name, objective);
  if (r.frames.size() > static_cast<size_t>(p.iterations))
    throw std::runtime_error(fmt::format("{} camera {}: {} search frames, the profile has {}",
                                         run_key, r.camera, r.frames.size(), p.iterations));
  if (!r.frames.empty()) {
    tuner::TunerOptions options = eval_tuner_options(p, objective, run_key, r.camera);
    options.db_path = eval_db_path(paths);
    options.hardware = r.hardware;
    tuner::HybridTuner tuner(eval_space(p), make_indicator_schema(), options);
    const std::vector<tuner::StoredSample> stored = tuner.database()->samples(tuner.signature_id());
    const tuner::State& state = scene.states[static_cast<size_t>(r.camera)];
    for (size_t i = 0; i < r.frames.size(); ++i) {
      if (i >= stored.size())
        replay_search_frame(tuner, state, r.frames[i]);
      else if (stored[i].config != r.frames[i].config)
        throw std::runtime_error(fmt::format(
            "{} camera {}: frame {} was {} in the database, {} on the rank that measured", run_key,
            r.camera, i, stored[i].config, r.frames[i].config));
    }
  }
  if (r.comparison)
    ComparisonLog(eval_comparisons_path(paths), run_key).add(r.camera, *r.comparison);
}

std::string mixed_ranks_message(const std::vector<std::string>& hardware_by_rank) {
  std::map<std::string, std::string> ranks;  // hardware -> "1, 2"
  for (size_t rank = 1; rank < hardware_by_rank.size(); ++rank) {
    std::string& list = ranks[hardware_by_rank[rank]];
    list += (list.empty() ? "" : ", ") + std::to_string(rank);
  }
  std::vector<std::string> machines;
  for (const auto& [h, list] : ranks) machines.push_back(fmt::format("{} (ranks {})", h, list));
  return mixed_machines_message(machines);
}

void stop_workers(RankTransport& transport) {
  for (int rank = 1; rank < transport.size(); ++rank) transport.send(rank, RankTag::kStop, "");
}

}  // namespace

void run_eval_worker(const EvalProfile& p, RankTransport& transport, const std::string& hardware) {
  try {
    transport.send(0, RankTag::kHello, hardware);
    int loaded = -1;
    std::unique_ptr<EvalScene> scene;
    std::map<int, std::unique_ptr<EvalCostSource>> costs;  // by objective, of the loaded scene
    for (;;) {
      const RankMessage m = transport.receive();
      if (m.tag == RankTag::kStop) return;
      if (m.tag != RankTag::kJob)
        throw std::runtime_error(
            fmt::format("unexpected message {} from rank {}", static_cast<int>(m.tag), m.from));
      const EvalJob job = parse_eval_job(m.body);
      check_indices(p, job.scene, job.objective, job.camera);
      if (job.scene != loaded) {
        costs.clear();  // they refer to the scene
        scene = load_eval_scene(p, p.scenes[static_cast<size_t>(job.scene)]);
        loaded = job.scene;
      }
      std::unique_ptr<EvalCostSource>& c = costs[job.objective];
      if (!c) c = make_eval_costs(p, *scene, p.objectives[static_cast<size_t>(job.objective)]);
      transport.send(0, RankTag::kResult, to_json(run_eval_job(p, *scene, *c, job, hardware)));
    }
  } catch (const std::exception& e) {
    transport.send(0, RankTag::kError, e.what());
  }
}

void dispatch_eval_jobs(RankTransport& transport, const std::vector<EvalJob>& jobs,
                        const std::function<void(int rank, const EvalJobResult&)>& store) {
  std::vector<bool> handed(jobs.size(), false);
  std::map<int, int> last_scene;  // by rank
  size_t outstanding = 0;
  auto hand_out = [&](int rank) {
    size_t pick = jobs.size();
    for (size_t i = 0; i < jobs.size(); ++i) {
      if (handed[i]) continue;
      if (pick == jobs.size()) pick = i;
      auto last = last_scene.find(rank);
      if (last != last_scene.end() && jobs[i].scene == last->second) {
        pick = i;
        break;
      }
    }
    if (pick == jobs.size()) return;
    handed[pick] = true;
    last_scene[rank] = jobs[pick].scene;
    ++outstanding;
    transport.send(rank, RankTag::kJob, to_json(jobs[pick]));
  };
  for (int rank = 1; rank < transport.size(); ++rank) hand_out(rank);
  while (outstanding > 0) {
    const RankMessage m = transport.receive();
    if (m.tag == RankTag::kError)
      throw std::runtime_error(fmt::format("rank {}: {}", m.from, m.body));
    if (m.tag != RankTag::kResult)
      throw std::runtime_error(
          fmt::format("unexpected message {} from rank {}", static_cast<int>(m.tag), m.from));
    --outstanding;
    store(m.from, parse_eval_job_result(m.body));
    hand_out(m.from);
  }
}

EvalResults run_eval_coordinator(const EvalProfile& p, const EvalPaths& paths,
                                 RankTransport& transport, bool mix_signatures,
                                 const std::function<void(const std::string&)>& progress,
                                 const std::function<void(const std::string&)>& log) {
  if (transport.size() < 2) throw std::invalid_argument("the coordinator needs a worker rank");
  try {
    std::vector<std::string> hardware_by_rank(static_cast<size_t>(transport.size()));
    for (int hellos = 0; hellos < transport.size() - 1; ++hellos) {
      const RankMessage m = transport.receive();
      if (m.tag == RankTag::kError)
        throw std::runtime_error(fmt::format("rank {}: {}", m.from, m.body));
      if (m.tag != RankTag::kHello)
        throw std::runtime_error(
            fmt::format("rank {} said {} before hello", m.from, static_cast<int>(m.tag)));
      hardware_by_rank[static_cast<size_t>(m.from)] = m.body;
    }
    EvalStudyOptions options;
    for (size_t rank = 1; rank < hardware_by_rank.size(); ++rank)
      if (std::find(options.hardware.begin(), options.hardware.end(), hardware_by_rank[rank]) ==
          options.hardware.end())
        options.hardware.push_back(hardware_by_rank[rank]);
    if (options.hardware.size() > 1 && !mix_signatures)
      throw EvalSignatureError(mixed_ranks_message(hardware_by_rank));
    options.mix_signatures = mix_signatures;

    std::map<int, std::unique_ptr<EvalScene>> scenes;  // loaded to replay searches
    for (int round = 1;; ++round) {
      EvalPlan plan;
      options.plan = &plan;
      std::vector<std::string> lines;
      EvalResults results = run_eval_study(
          p, paths, [&](const std::string& line) { lines.push_back(line); }, options);
      if (plan.jobs.empty()) {
        stop_workers(transport);
        if (log)
          for (const std::string& line : lines) log(line);
        return results;
      }
      if (round == kMaxRounds)
        throw std::runtime_error(fmt::format(
            "after {} rounds the study still lacks {} jobs' results: the ranks do not deliver "
            "what they are asked (do all run the same program?)",
            kMaxRounds, plan.jobs.size()));
      size_t stored = 0;
      dispatch_eval_jobs(transport, plan.jobs, [&](int rank, const EvalJobResult& r) {
        check_indices(p, r.scene, r.objective, r.camera);
        std::unique_ptr<EvalScene>& scene = scenes[r.scene];
        if (!scene) scene = load_eval_scene(p, p.scenes[static_cast<size_t>(r.scene)]);
        store_result(p, paths, *scene, r);
        ++stored;
        if (progress)
          progress(
              fmt::format("round {}: {}/{} stored; rank {}: {} {} camera {}, {} search "
                          "frames, {} configurations compared in {} rounds",
                          round, stored, plan.jobs.size(), rank, scene->name,
                          to_string(p.objectives[static_cast<size_t>(r.objective)]), r.camera,
                          r.frames.size(), r.comparison ? r.comparison->configs.size() : 0,
                          r.comparison ? r.comparison->rounds() : 0));
      });
    }
  } catch (...) {
    // Workers that still wait for a job must not wait forever (under MPI the caller aborts).
    stop_workers(transport);
    throw;
  }
}

}  // namespace tuneray
