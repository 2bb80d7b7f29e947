// An append-only log of measured costs (key TAB milliseconds per line) that survives kills: the
// study appends each measurement as it is made and reads the log back when it resumes. A line
// cut short by a kill is never read as a value (a torn "0.123456" would read as 0.12): only
// whole lines count, and the next append first closes a torn line with a mark that keeps it
// from ever parsing.
#pragma once

#include <map>
#include <optional>
#include <string>

namespace tuneray {

class CostLog {
 public:
  // Reads the complete lines of `path` whose key starts with `prefix` (a missing file is empty).
  CostLog(std::string path, std::string prefix);

  std::optional<double> find(const std::string& key) const;
  // Records and appends `key TAB ms`; ms is kept with the 6 decimals it is written with, and
  // that kept value is returned: callers must use it, not `ms`, or a run that reads the log back
  // after a kill sees other bits than the run that wrote it.
  double add(const std::string& key, double ms);
  // Every known entry, by key.
  const std::map<std::string, double>& entries() const { return entries_; }

 private:
  std::string path_, prefix_;
  std::map<std::string, double> entries_;
  bool torn_tail_ = false;  // the file ends in a partial line: start the next append afresh
};

}  // namespace tuneray
