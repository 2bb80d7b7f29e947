#include "tuning/line_log.h"

#include <fstream>
#include <iterator>
#include <stdexcept>

namespace tuneray {

LineLog::LineLog(std::string path, std::string prefix)
    : path_(std::move(path)), prefix_(std::move(prefix)) {
  std::ifstream in(path_, std::ios::binary);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  size_t start = 0;
  for (size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1) {
    const std::string line = text.substr(start, end - start);
    const size_t tab = line.rfind('\t');
    if (tab == std::string::npos || line.compare(0, prefix_.size(), prefix_) != 0) continue;
    entries_[line.substr(0, tab)] = line.substr(tab + 1);
  }
  torn_tail_ = start < text.size();
}

std::optional<std::string> LineLog::find(const std::string& key) const {
  if (auto it = entries_.find(key); it != entries_.end()) return it->second;
  return std::nullopt;
}

void LineLog::add(const std::string& key, const std::string& value) {
  if (key.compare(0, prefix_.size(), prefix_) != 0 || key.find('\n') != std::string::npos ||
      value.find_first_of("\t\n") != std::string::npos)
    throw std::invalid_argument("log line '" + key + "' would not read back as written");
  std::ofstream out(path_, std::ios::app | std::ios::binary);
  // The torn line is closed with a mark that keeps it from ever parsing as a value.
  if (torn_tail_) out << " (torn by a kill)\n";
  out << key << '\t' << value << '\n';
  out.flush();
  if (!out) throw std::runtime_error("cannot append to " + path_);
  torn_tail_ = false;
  entries_[key] = value;
}

}  // namespace tuneray
