#include "tuning/tree_cache.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace tuneray {

TunedTreeCache::TunedTreeCache(size_t capacity) : capacity_(capacity) {
  if (capacity == 0) throw std::invalid_argument("a tree cache needs room for one tree");
}

bool TunedTreeCache::take(const std::string& key, const std::optional<std::string>& current,
                          TunedBvhAccel& accel, BuildStats& stats) {
  auto it =
      std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.key == key; });
  if (it == entries_.end()) return false;
  accel.swap_tree(*it->tree);
  std::swap(stats, it->stats);
  if (!current) {  // `accel` had no tree (a refused build): nothing to keep in exchange
    entries_.erase(it);
    return true;
  }
  it->key = *current;
  entries_.splice(entries_.begin(), entries_, it);
  return true;
}

void TunedTreeCache::keep(const std::string& key, TunedBvhAccel& accel, const BuildStats& stats) {
  std::unique_ptr<TunedBvhAccel> holder;
  if (entries_.size() >= capacity_) {
    // Release the evicted tree now, not when the next build finishes: one tree less at the peak.
    holder = std::move(entries_.back().tree);
    entries_.pop_back();
    TunedBvhAccel empty;
    holder->swap_tree(empty);
  } else {
    // The shared device keeps Embree alive as long as a kept tree.
    holder = std::make_unique<TunedBvhAccel>();
  }
  accel.swap_tree(*holder);
  entries_.push_front(Entry{key, std::move(holder), stats});
}

}  // namespace tuneray
