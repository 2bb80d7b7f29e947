// The tuned trees a FrameBench keeps besides the one it renders with, so that frames which
// alternate between a few configurations (a comparison's rounds) do not rebuild a tree for
// every frame. Trees are exchanged with the rendering accelerator (TunedBvhAccel::swap_tree),
// never copied, so a tree taken from here is the very tree that was built: its frames are
// bit-identical to the first build's. Bounded: at most `capacity` trees are kept and the least
// recently used one is released first (see FrameBench for why the bound).
#pragma once

#include <cstddef>
#include <list>
#include <memory>
#include <optional>
#include <string>

#include "accel/accel.h"
#include "accel/tuned_bvh.h"

namespace tuneray {

class TunedTreeCache {
 public:
  explicit TunedTreeCache(size_t capacity);

  // When a tree of `key` is kept, exchanges it with `accel`'s current tree (and its build
  // statistics with `stats`): `accel`'s tree, built for `current` when it has one, is kept in
  // its place as the most recently used. False, changing nothing, when no tree of `key` is kept.
  bool take(const std::string& key, const std::optional<std::string>& current, TunedBvhAccel& accel,
            BuildStats& stats);
  // Keeps `accel`'s tree, built for `key` with `stats`, as the most recently used, releasing the
  // least recently used one if the cache is full; `accel` is left without a tree.
  void keep(const std::string& key, TunedBvhAccel& accel, const BuildStats& stats);

  size_t size() const { return entries_.size(); }
  size_t capacity() const { return capacity_; }

 private:
  struct Entry {
    std::string key;
    std::unique_ptr<TunedBvhAccel> tree;  // holds the tree only (it never builds)
    BuildStats stats;
  };
  size_t capacity_;
  std::list<Entry> entries_;  // most recently used first
};

}  // namespace tuneray
