#include "tuning/mpi_ranks.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <thread>

#include "tuning/rank_cores.h"

#ifdef TUNERAY_HAVE_MPI
#include <mpi.h>
#include <sched.h>
#endif

namespace tuneray {

int mpirun_world_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
    if (const char* value = std::getenv(name)) return std::max(1, std::atoi(value));
  return 0;
}

#ifdef TUNERAY_HAVE_MPI

bool mpi_compiled_in() {
  return true;
}

namespace {

class MpiTransport : public RankTransport {
 public:
  MpiTransport(int rank, int size) : rank_(rank), size_(size) {}
  int rank() const override { return rank_; }
  int size() const override { return size_; }

  void send(int to, RankTag tag, const std::string& body) override {
    MPI_Send(body.data(), static_cast<int>(body.size()), MPI_CHAR, to, static_cast<int>(tag),
             MPI_COMM_WORLD);
  }

  RankMessage receive() override {
    MPI_Status status;
    int arrived = 0;
    auto pause = std::chrono::microseconds(50);
    for (;;) {
      MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status);
      if (arrived) break;
      std::this_thread::sleep_for(pause);
      pause = std::min(pause * 2, std::chrono::microseconds(5000));
    }
    int count = 0;
    MPI_Get_count(&status, MPI_CHAR, &count);
    RankMessage m;
    m.from = status.MPI_SOURCE;
    m.tag = static_cast<RankTag>(status.MPI_TAG);
    m.body.resize(static_cast<size_t>(count));
    MPI_Recv(m.body.data(), count, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    return m;
  }

 private:
  int rank_, size_;
};

}  // namespace

MpiSession::MpiSession() {
  MPI_Init(nullptr, nullptr);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  MPI_Finalize();
}

std::unique_ptr<RankTransport> MpiSession::transport() {
  return std::make_unique<MpiTransport>(rank_, size_);
}

MpiSession::Node MpiSession::node() {
  MPI_Comm local;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &local);
  int local_size = 0;
  MPI_Comm_size(local, &local_size);
  Node n;
  n.ranks.resize(static_cast<size_t>(local_size));
  MPI_Allgather(&rank_, 1, MPI_INT, n.ranks.data(), 1, MPI_INT, local);
  std::vector<char> mine(CPU_SETSIZE, 0);
  for (int c : process_cores()) mine[static_cast<size_t>(c)] = 1;
  std::vector<char> all(static_cast<size_t>(CPU_SETSIZE) * static_cast<size_t>(local_size));
  MPI_Allgather(mine.data(), CPU_SETSIZE, MPI_CHAR, all.data(), CPU_SETSIZE, MPI_CHAR, local);
  MPI_Comm_free(&local);
  for (int c = 0; c < CPU_SETSIZE; ++c)
    for (int r = 0; r < local_size; ++r)
      if (all[static_cast<size_t>(r) * CPU_SETSIZE + static_cast<size_t>(c)]) {
        n.cores.push_back(c);
        break;
      }
  return n;
}

void MpiSession::abort(int code) {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);  // MPI_Abort does not return; this keeps [[noreturn]] honest
}

#else

bool mpi_compiled_in() {
  return false;
}

MpiSession::MpiSession() {
  throw std::runtime_error(
      "this tuneray was built without MPI (install libopenmpi-dev and reconfigure)");
}

MpiSession::~MpiSession() = default;

std::unique_ptr<RankTransport> MpiSession::transport() {
  return nullptr;
}

MpiSession::Node MpiSession::node() {
  return {};
}

void MpiSession::abort(int code) {
  std::exit(code);
}

#endif

}  // namespace tuneray
