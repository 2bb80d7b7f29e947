// An append-only log of KEY TAB VALUE lines that survives kills: the study appends each result
// as it is made and reads the log back when it resumes. A line cut short by a kill is never
// read as a value (a torn "0.123456" would read as 0.12): only whole lines count, and the next
// append first closes a torn line with a mark that keeps it from ever parsing. A key written
// again later replaces its earlier value.
#pragma once

#include <map>
#include <optional>
#include <string>

namespace tuneray {

class LineLog {
 public:
  // Reads the complete lines of `path` whose key starts with `prefix` (a missing file is empty).
  LineLog(std::string path, std::string prefix);

  std::optional<std::string> find(const std::string& key) const;
  // Records and appends `key TAB value`. Throws std::invalid_argument when the key does not
  // start with the prefix or either holds a line break, or the value a tab (the line would not
  // read back as written); std::runtime_error when the file cannot be appended to.
  void add(const std::string& key, const std::string& value);

 private:
  std::string path_, prefix_;
  std::map<std::string, std::string> entries_;
  bool torn_tail_ = false;  // the file ends in a partial line: start the next append afresh
};

}  // namespace tuneray
