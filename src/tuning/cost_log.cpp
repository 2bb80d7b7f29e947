#include "tuning/cost_log.h"

#include <fmt/core.h>

#include <fstream>
#include <iterator>
#include <stdexcept>

namespace tuneray {

CostLog::CostLog(std::string path, std::string prefix)
    : path_(std::move(path)), prefix_(std::move(prefix)) {
  std::ifstream in(path_, std::ios::binary);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  size_t start = 0;
  for (size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1) {
    const std::string line = text.substr(start, end - start);
    const size_t tab = line.rfind('\t');
    if (tab == std::string::npos || line.compare(0, prefix_.size(), prefix_) != 0) continue;
    try {
      size_t used = 0;
      const double ms = std::stod(line.substr(tab + 1), &used);
      if (used == line.size() - tab - 1) entries_[line.substr(0, tab)] = ms;
    } catch (const std::exception&) {  // not a number: a line mangled by an earlier torn write
    }
  }
  torn_tail_ = start < text.size();
}

std::optional<double> CostLog::find(const std::string& key) const {
  if (auto it = entries_.find(key); it != entries_.end()) return it->second;
  return std::nullopt;
}

double CostLog::add(const std::string& key, double ms) {
  // Kept as it will be read back, so a resumed run sees exactly the values of an uninterrupted one.
  const std::string text = fmt::format("{:.6f}", ms);
  const double kept = std::stod(text);
  entries_[key] = kept;
  std::ofstream out(path_, std::ios::app | std::ios::binary);
  // The torn line is closed with a mark that keeps it from ever parsing as a value.
  if (torn_tail_) out << " (torn by a kill)\n";
  out << key << '\t' << text << '\n';
  out.flush();
  if (!out) throw std::runtime_error("cannot append to " + path_);
  torn_tail_ = false;
  return kept;
}

}  // namespace tuneray
