#include "tuning/rank_cores.h"

#include <fmt/core.h>
#include <sched.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace tuneray {

std::map<int, std::vector<int>> split_node_cores(const std::vector<int>& node_ranks,
                                                 const std::vector<int>& cores) {
  std::vector<int> workers;
  for (int r : node_ranks)
    if (r != 0) workers.push_back(r);
  std::sort(workers.begin(), workers.end());
  std::map<int, std::vector<int>> split;
  if (workers.empty() || cores.empty()) return split;
  const size_t w = workers.size(), n = cores.size();
  if (w > n) {
    for (size_t i = 0; i < w; ++i) split[workers[i]] = {cores[i % n]};
    return split;
  }
  size_t next = 0;
  for (size_t i = 0; i < w; ++i) {
    const size_t count = n / w + (i < n % w ? 1 : 0);
    split[workers[i]].assign(cores.begin() + static_cast<long>(next),
                             cores.begin() + static_cast<long>(next + count));
    next += count;
  }
  return split;
}

std::string core_list_text(const std::vector<int>& cores) {
  std::string text;
  for (size_t i = 0; i < cores.size();) {
    size_t j = i;
    while (j + 1 < cores.size() && cores[j + 1] == cores[j] + 1) ++j;
    if (!text.empty()) text += ",";
    text += j == i ? std::to_string(cores[i]) : fmt::format("{}-{}", cores[i], cores[j]);
    i = j + 1;
  }
  return text;
}

std::string describe_node_cores(const std::vector<int>& node_ranks, const std::vector<int>& cores,
                                const std::map<int, std::vector<int>>& split) {
  std::vector<int> ranks = node_ranks;
  std::sort(ranks.begin(), ranks.end());
  std::string text = fmt::format("{} rank{} on this node share{} {} core{}", ranks.size(),
                                 ranks.size() == 1 ? "" : "s", ranks.size() == 1 ? "s" : "",
                                 cores.size(), cores.size() == 1 ? "" : "s");
  size_t measuring = 0;
  for (int r : ranks) measuring += r != 0;
  if (measuring > cores.size())
    text += " (more measuring ranks than cores: they share cores and time each other's frames)";
  text += ":";
  for (size_t i = 0; i < ranks.size(); ++i) {
    text += i ? ", " : " ";
    auto it = split.find(ranks[i]);
    if (ranks[i] == 0)
      text += "rank 0 coordinates (no core of its own)";
    else if (it != split.end())
      text += fmt::format("rank {} on core{} {}", ranks[i], it->second.size() == 1 ? "" : "s",
                          core_list_text(it->second));
  }
  return text;
}

std::vector<int> process_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) != 0)
    throw std::runtime_error(std::string("sched_getaffinity: ") + std::strerror(errno));
  std::vector<int> cores;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &set)) cores.push_back(c);
  return cores;
}

void pin_process(const std::vector<int>& cores) {
  cpu_set_t set;
  CPU_ZERO(&set);
  for (int c : cores) {
    if (c < 0 || c >= CPU_SETSIZE) throw std::runtime_error(fmt::format("no core {}", c));
    CPU_SET(c, &set);
  }
  if (sched_setaffinity(0, sizeof(set), &set) != 0)
    throw std::runtime_error(
        fmt::format("cannot pin to cores {}: {}", core_list_text(cores), std::strerror(errno)));
}

}  // namespace tuneray
