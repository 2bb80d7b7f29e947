// MPI as seen by the study: whether this process was started by mpirun, and a session (MPI_Init
// to MPI_Finalize) whose transport carries the study's messages. Built without MPI (the package
// was absent at configure time), mpi_compiled_in() is false and a session cannot be opened.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "tuning/rank_transport.h"

namespace tuneray {

bool mpi_compiled_in();

// The number of processes mpirun (OpenMPI, or a PMI launcher) started, read from the
// environment it gives them; 0 when this process was not started by mpirun. Decides whether to
// initialise MPI at all, so that a plain `tuneray eval` never touches it.
int mpirun_world_size();

class MpiSession {
 public:
  // MPI_Init; throws std::runtime_error when built without MPI.
  MpiSession();
  ~MpiSession();  // MPI_Finalize
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  // Messages over MPI_COMM_WORLD. receive() polls with growing sleeps instead of blocking in
  // MPI_Recv, which spins a core at 100 %: rank 0 waits for results most of the time, on a core
  // the measuring ranks of its node need.
  std::unique_ptr<RankTransport> transport();

  // World ranks on this node (MPI_COMM_TYPE_SHARED) and the union of their affinity masks:
  // mpirun may have bound each rank to one core of its own choice. Collective: every rank calls.
  struct Node {
    std::vector<int> ranks;
    std::vector<int> cores;
  };
  Node node();

  // Ends every rank of the job (a failing coordinator would otherwise leave workers waiting).
  [[noreturn]] void abort(int code);

 private:
  int rank_ = 0, size_ = 1;
};

}  // namespace tuneray
