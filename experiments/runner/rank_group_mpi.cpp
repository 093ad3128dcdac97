// The rank group over MPI (CLOSURELAB_WITH_MPI=ON): MPI_Init/Finalize and the master/worker exchange. Rank 0
// answers each request of a worker with a task or "stop"; a worker's result is also its request for the next
// task. Both sides wait by polling (MPI_Iprobe and a short sleep) rather than in a blocking receive, which Open MPI
// spins in: a rank waiting for a long cell elsewhere must not take a core from the cells.
// The C interface only (Open MPI's and MPICH's C++ bindings are deprecated and need their own library).
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <thread>

#include "experiments/runner/rank_group.hpp"

namespace closurelab {

namespace {

enum Tag : int { kReady = 1, kResult = 2, kTask = 3, kStop = 4 };

// Whether a process manager (mpirun, mpiexec, srun) started this process as an MPI rank.
bool started_as_mpi_rank() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(var)) return true;
  return false;
}

// Waits (polling) for a message from `source` (or any), then receives it whole as text.
std::string receive(int source, MPI_Status& status) {
  for (int flag = 0;;) {
    MPI_Iprobe(source, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
    if (flag) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  int count = 0;
  MPI_Get_count(&status, MPI_CHAR, &count);
  std::string text(static_cast<std::size_t>(count), '\0');
  MPI_Recv(text.data(), count, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return text;
}

void send(const std::string& text, int dest, int tag) {
  MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, dest, tag, MPI_COMM_WORLD);
}

}  // namespace

RankGroup::RankGroup() {
  if (!started_as_mpi_rank()) return;
  int already = 0;
  MPI_Initialized(&already);
  if (!already) {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    initialized_here_ = true;
  }
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

RankGroup::~RankGroup() {
  if (initialized_here_) MPI_Finalize();
}

void RankGroup::serve(const std::function<std::optional<std::string>(int)>& next_task,
                      const std::function<void(const std::string&, int)>& on_result) const {
  for (int active = size_ - 1; active > 0;) {
    MPI_Status status;
    const std::string text = receive(MPI_ANY_SOURCE, status);
    if (status.MPI_TAG == kResult) on_result(text, status.MPI_SOURCE);
    if (const auto task = next_task(status.MPI_SOURCE)) {
      send(*task, status.MPI_SOURCE, kTask);
    } else {
      send("", status.MPI_SOURCE, kStop);
      --active;
    }
  }
}

void RankGroup::abort(int code) const {
  if (size_ > 1) MPI_Abort(MPI_COMM_WORLD, code);
}

void RankGroup::work(const std::function<std::string(const std::string&)>& compute) const {
  send("", 0, kReady);
  for (;;) {
    MPI_Status status;
    const std::string task = receive(0, status);
    if (status.MPI_TAG == kStop) return;
    std::string result;
    try {
      result = compute(task);
    } catch (const std::exception& e) {
      std::cerr << "error: rank " << rank_ << ": " << e.what() << "\n";
      MPI_Abort(MPI_COMM_WORLD, 1);
    }
    send(result, 0, kResult);
  }
}

}  // namespace closurelab
