#pragma once
// The ranks of one run. Under `mpirun -n K closurelab run ...` (built with CLOSURELAB_WITH_MPI) they are the K MPI
// processes: rank 0 validates the matrix, hands out cells and writes every result; ranks 1..K-1 compute the cells
// they are handed. Otherwise (no mpirun, or built without MPI: rank_group_serial.cpp) there is one rank.
// This is the only place that knows MPI (rank_group_mpi.cpp). Tasks and results travel as text (JSON); what a
// task means is the runner's business.
#include <functional>
#include <optional>
#include <string>

namespace closurelab {

class RankGroup {
 public:
  // Initializes MPI (MPI_THREAD_FUNNELED: only the thread that made the group calls MPI) when this process was
  // started by mpirun; otherwise a group of one.
  RankGroup();
  ~RankGroup();  // MPI_Finalize, if it was initialized here
  RankGroup(const RankGroup&) = delete;
  RankGroup& operator=(const RankGroup&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }

  // Rank 0: serves the other ranks until each has been told to stop. `next_task(rank)` gives the text of the
  // next task for that rank, or nothing when there is none left (the rank is then told to stop); every result a
  // rank sends back goes to `on_result(result, rank)` before that rank's next task is asked for. Waiting polls with
  // short sleeps, so a waiting rank 0 does not take a core from the cells. Returns at once in a group of one.
  void serve(const std::function<std::optional<std::string>(int rank)>& next_task,
             const std::function<void(const std::string& result, int rank)>& on_result) const;

  // Ends every rank of the run at once (MPI_Abort) with `code`, when an error leaves rank 0 unable to release
  // the others; returns (doing nothing) in a group of one.
  void abort(int code) const;

  // Ranks > 0: asks rank 0 for tasks, computes each with `compute` and sends back its result; returns when rank 0
  // says stop.
  void work(const std::function<std::string(const std::string& task)>& compute) const;

 private:
  int rank_ = 0;
  int size_ = 1;
  bool initialized_here_ = false;
};

}  // namespace closurelab
