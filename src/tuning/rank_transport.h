// Messages between the ranks of a study spread over processes: an interface, so that the job
// distribution runs over MPI in the program and over in-process queues in tests.
#pragma once

#include <string>

namespace tuneray {

enum class RankTag : int {
  kHello = 1,  // worker -> coordinator: ready; body = the worker's hardware signature
  kJob,        // coordinator -> worker: an EvalJob
  kResult,     // worker -> coordinator: an EvalJobResult, which also asks for the next job
  kError,      // worker -> coordinator: the job failed; body = why. The worker stops.
  kStop,       // coordinator -> worker: no more jobs
};

struct RankMessage {
  int from = 0;
  RankTag tag = RankTag::kStop;
  std::string body;
};

class RankTransport {
 public:
  virtual ~RankTransport() = default;
  virtual int rank() const = 0;  // 0 is the coordinator
  virtual int size() const = 0;
  virtual void send(int to, RankTag tag, const std::string& body) = 0;
  // Blocks until a message for this rank arrives, from any rank.
  virtual RankMessage receive() = 0;
};

}  // namespace tuneray
