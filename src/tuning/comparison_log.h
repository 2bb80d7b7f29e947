// The study's finished comparisons (eval_comparison.h), one whole line per camera in
// `comparisons.tsv` beside the report, so that a study killed at any moment and run again
// measures no finished comparison twice. A comparison is written only when its last round is
// done: a kill mid-comparison leaves nothing of it, and the rerun measures that camera's
// comparison again from its first round, in one time window.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "tuning/eval_comparison.h"
#include "tuning/line_log.h"

namespace tuneray {

class ComparisonLog {
 public:
  // The comparisons of one scene and objective (`run_key`, eval_search.h) in the file `path`.
  ComparisonLog(const std::string& path, const std::string& run_key);

  // The stored comparison of `camera` if it measured exactly `configs`, in that order (one of
  // other configurations, from a study of other sizes, does not count).
  std::optional<EvalComparison> find(int camera, const std::vector<std::string>& configs) const;
  // Appends the comparison of `camera` and returns it as it reads back, which callers must use
  // so that a resumed run sees the bits an uninterrupted one saw.
  EvalComparison add(int camera, const EvalComparison& comparison);

 private:
  std::string key(int camera) const;

  std::string run_key_;
  LineLog log_;
};

}  // namespace tuneray
