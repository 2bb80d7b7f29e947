// The study spread over ranks. Rank 0 coordinates: it alone opens the tuning database, the
// comparison log and the report; it plans what is missing (run_eval_study with a plan), hands the
// jobs out one at a time to whichever worker asks next (jobs differ in cost by 100x, so a fixed
// split would leave ranks idle), and stores each result as it arrives, so a killed run loses
// nothing already reported and resumes with any number of ranks. Rank 0 measures nothing: it
// waits for messages without spinning, so the cores of its node go to the workers there.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "tuning/eval_job.h"
#include "tuning/eval_study.h"
#include "tuning/rank_transport.h"

namespace tuneray {

// Worker ranks: say hello with `hardware`, then run jobs until told to stop. Throws nothing: a
// failure is sent to the coordinator (kError) and ends the worker.
void run_eval_worker(const EvalProfile& p, RankTransport& transport, const std::string& hardware);

// Rank 0: the whole study with transport.size() - 1 workers; returns what run_eval_study
// returns. Throws on a worker's error (whose message names the rank), on mixed signatures
// unless options.mix_signatures, and when the workers fail to deliver what the plan asked.
// `progress` receives a line per stored job; `log` the study's per-camera lines at the end.
EvalResults run_eval_coordinator(const EvalProfile& p, const EvalPaths& paths,
                                 RankTransport& transport, bool mix_signatures,
                                 const std::function<void(const std::string&)>& progress,
                                 const std::function<void(const std::string&)>& log);

// Hands `jobs` out to `idle` workers one at a time: a worker gets a job of the scene it last
// worked on when one is left (it has that scene loaded), else the next in order. Calls `store`
// for each result as it arrives. Returns when every job's result has arrived.
void dispatch_eval_jobs(RankTransport& transport, const std::vector<EvalJob>& jobs,
                        const std::function<void(int rank, const EvalJobResult&)>& store);

}  // namespace tuneray
