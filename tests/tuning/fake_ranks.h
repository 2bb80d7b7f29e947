// In-process ranks for tests of the study's job distribution without MPI: one message queue per
// rank, each rank a RankTransport over the shared queues (workers run in threads).
#pragma once

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <vector>

#include "tuning/rank_transport.h"

namespace tuneray::testing {

class FakeRanks {
 public:
  explicit FakeRanks(int size) : queues_(static_cast<size_t>(size)) {}

  std::unique_ptr<RankTransport> transport(int rank) {
    return std::make_unique<Transport>(*this, rank);
  }
  int size() const { return static_cast<int>(queues_.size()); }

 private:
  struct Queue {
    std::deque<RankMessage> messages;
  };

  class Transport : public RankTransport {
   public:
    Transport(FakeRanks& ranks, int rank) : ranks_(ranks), rank_(rank) {}
    int rank() const override { return rank_; }
    int size() const override { return ranks_.size(); }
    void send(int to, RankTag tag, const std::string& body) override {
      std::lock_guard lock(ranks_.mutex_);
      ranks_.queues_.at(static_cast<size_t>(to)).messages.push_back({rank_, tag, body});
      ranks_.arrived_.notify_all();
    }
    RankMessage receive() override {
      std::unique_lock lock(ranks_.mutex_);
      auto& q = ranks_.queues_[static_cast<size_t>(rank_)].messages;
      ranks_.arrived_.wait(lock, [&] { return !q.empty(); });
      RankMessage m = std::move(q.front());
      q.pop_front();
      return m;
    }

   private:
    FakeRanks& ranks_;
    int rank_;
  };

  std::mutex mutex_;
  std::condition_variable arrived_;
  std::vector<Queue> queues_;
};

// Wraps a transport: counts the jobs sent and, after `results_before_failure` results were
// received, throws from receive() — rank 0 killed after storing that many results.
class InterruptedTransport : public RankTransport {
 public:
  InterruptedTransport(RankTransport& inner, int results_before_failure)
      : inner_(inner), left_(results_before_failure) {}
  int rank() const override { return inner_.rank(); }
  int size() const override { return inner_.size(); }
  void send(int to, RankTag tag, const std::string& body) override {
    if (tag == RankTag::kJob) ++jobs_sent;
    inner_.send(to, tag, body);
  }
  RankMessage receive() override {
    if (left_ == 0) throw std::runtime_error("interrupted");
    RankMessage m = inner_.receive();
    if (m.tag == RankTag::kResult && left_ > 0) --left_;
    return m;
  }
  int jobs_sent = 0;

 private:
  RankTransport& inner_;
  int left_;  // < 0: never
};

}  // namespace tuneray::testing
