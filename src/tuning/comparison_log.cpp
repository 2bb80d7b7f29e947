#include "tuning/comparison_log.h"

#include <fmt/core.h>

#include <stdexcept>

namespace tuneray {

ComparisonLog::ComparisonLog(const std::string& path, const std::string& run_key)
    : run_key_(run_key), log_(path, run_key + '\t') {}

std::string ComparisonLog::key(int camera) const {
  return fmt::format("{}\t{}", run_key_, camera);
}

std::optional<EvalComparison> ComparisonLog::find(int camera,
                                                  const std::vector<std::string>& configs) const {
  const std::optional<std::string> text = log_.find(key(camera));
  if (!text) return std::nullopt;
  try {
    EvalComparison stored = parse_eval_comparison(*text);
    if (stored.configs == configs) return stored;
  } catch (const std::runtime_error&) {  // a line closed by the mark of a torn write
  }
  return std::nullopt;
}

EvalComparison ComparisonLog::add(int camera, const EvalComparison& comparison) {
  const std::string text = to_json(comparison);
  log_.add(key(camera), text);
  return parse_eval_comparison(text);
}

}  // namespace tuneray
