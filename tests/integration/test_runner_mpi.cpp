// A matrix over MPI ranks (mpirun -n 2 --oversubscribe closurelab run ...): the table equals the serial one except
// timings and provenance, also for reduced-model cells that share a direct reference (computed once per rank), and
// each row records the run's ranks; a re-run resumes from the finished cells (nothing computed, the table
// unchanged; one cell file removed: that cell alone is computed); an invalid spec exits 2 on rank 0 and releases
// the other rank (no hang); --jobs with several ranks is refused. Skipped in a build without MPI
// (CLOSURELAB_WITH_MPI=OFF). Takes about 11 s: mpirun's start and end, ~0.8 s a launch, ~2.7 s for a failed one
// (mpirun's teardown).
#include <gtest/gtest.h>

#include "core/base/params.hpp"
#include "tests/support/cli_run.hpp"
#include "tests/support/table_compare.hpp"

namespace fs = std::filesystem;
using closurelab::json;
using namespace closurelab::testing;

namespace {

const char* spec = R"({"name": "ranks", "kind": "direct_sph_validation",
  "base": {"scene": {"name": "poiseuille-uniform", "n_y": 16}, "solver": {"mode": "target_time", "target_time": 0.02}},
  "axes": {"solver.target_time": [0.02, 0.04, 0.03], "scene.n_y": [16, 20]}})";

json read(const fs::path& p) { return closurelab::read_json_file(p.string()); }

// `mpirun -n 2 closurelab ARGS`, allowed as root (CI runs as root), one OpenMP thread a rank, not bound to a core
// (two tests at once would pin their ranks to the same cores), killed after 120 s should the ranks ever wait on
// each other forever.
CliOutcome mpirun_closurelab(const fs::path& work, const std::string& args) {
  return run_shell(work, "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 timeout 120 " +
                             std::string(CLOSURELAB_MPIEXEC) + " -n 2 --oversubscribe --bind-to none " + CLOSURELAB_BINARY_DIR +
                             "/experiments/closurelab " + args);
}

bool have_mpi() {
  return CLOSURELAB_WITH_MPI && std::string(CLOSURELAB_MPIEXEC).find("NOTFOUND") == std::string::npos &&
         !std::string(CLOSURELAB_MPIEXEC).empty();
}

}  // namespace

TEST(RunnerMpi, TwoRanksGiveTheSerialTableAndAReRunResumes) {
  if (!have_mpi()) GTEST_SKIP() << "built without MPI (CLOSURELAB_WITH_MPI=OFF) or no mpiexec";
  const auto work = fresh_work_folder("mpi_table");
  write_text(work / "ranks.json", spec);
  const std::string spec_arg = (work / "ranks.json").string();
  const CliOutcome serial = run_closurelab(work, "run " + spec_arg + " --out " + (work / "serial").string());
  ASSERT_EQ(serial.code, 0) << serial.err;
  const CliOutcome mpi = mpirun_closurelab(work, "run " + spec_arg + " --out " + (work / "mpi").string());
  ASSERT_EQ(mpi.code, 0) << mpi.err;
  // The store summary comes from rank 0 alone (it used to be printed by every rank, interleaved).
  std::size_t summaries = 0;
  for (std::size_t at = mpi.err.find("reference store "); at != std::string::npos;
       at = mpi.err.find("reference store ", at + 1))
    ++summaries;
  EXPECT_EQ(summaries, 1u) << mpi.err;
  const json a = read(work / "serial" / "ranks.json"), b = read(work / "mpi" / "ranks.json");
  EXPECT_EQ(without_timings(a), without_timings(b));
  for (const json& row : b.at("rows")) {
    EXPECT_EQ(row.at("provenance").at("ranks"), 2);
    EXPECT_EQ(row.at("provenance").at("threads"), 1);
    const int rank = row.at("provenance").at("rank").get<int>();
    EXPECT_TRUE(rank == 0 || rank == 1) << rank;  // which rank computes which cell is up to the timing
  }
  for (const json& row : a.at("rows")) EXPECT_EQ(row.at("provenance").at("ranks"), 1);

  // Resume: every cell is on disk, so a second MPI run computes nothing and leaves the table byte-identical.
  const std::string before = read_text(work / "mpi" / "ranks.json");
  const CliOutcome again = mpirun_closurelab(work, "run " + spec_arg + " --out " + (work / "mpi").string());
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_NE(again.err.find("0 computed, 6 cached"), std::string::npos) << again.err;
  EXPECT_EQ(read_text(work / "mpi" / "ranks.json"), before);
  // A job killed after some cells: the missing cell alone is computed again, and the table is the serial one.
  fs::remove(work / "mpi" / "cells" / (b.at("rows").at(4).at("id").get<std::string>() + ".json"));
  const CliOutcome resumed = mpirun_closurelab(work, "run " + spec_arg + " --out " + (work / "mpi").string());
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("1 computed, 5 cached"), std::string::npos) << resumed.err;
  EXPECT_EQ(without_timings(read(work / "mpi" / "ranks.json")), without_timings(a));
}

TEST(RunnerMpi, ReducedModelCellsSharingADirectReferenceGiveTheSerialTable) {
  if (!have_mpi()) GTEST_SKIP() << "built without MPI (CLOSURELAB_WITH_MPI=OFF) or no mpiexec";
  // Three closures on one kolmogorov scene: each rank runs the shared direct reference itself (once per process).
  const auto work = fresh_work_folder("mpi_reduced");
  write_text(work / "rm.json", R"({"name": "rm", "kind": "reduced_model",
    "base": {"scene": {"name": "kolmogorov", "n_y": 32, "k": 4, "eta_over_ly": 0.0625},
             "quadrature": {"name": "coarse", "stride_x": 0, "stride_y": 1},
             "solver": {"mode": "target_time", "target_time": 0.02, "spacing_over_eta": 0.5, "scheme": "staggered"},
             "reference": {"direct_sph": true, "solver": {"mode": "target_time", "target_time": 0.02}}},
    "cells": [{"label": "lw0", "closure.deconvolver": {"name": "landweber", "order": 0}},
              {"label": "lw1", "closure.deconvolver": {"name": "landweber", "order": 1}},
              {"label": "cgls", "closure.deconvolver": {"name": "cgls", "iterations": 5},
               "closure.discretization": "coarse_fine"}]})");
  const std::string spec_arg = (work / "rm.json").string();
  // One thread, as each rank has: the pair sums reduce per thread, so another thread count moves the results
  // at round-off (and a CGLS stopping test with them), whatever scripts/test.sh sets for the whole suite.
  const CliOutcome serial = run_shell(work, "OMP_NUM_THREADS=1 " + std::string(CLOSURELAB_BINARY_DIR) +
                                                "/experiments/closurelab run " + spec_arg + " --out " +
                                                (work / "serial").string());
  ASSERT_EQ(serial.code, 0) << serial.err;
  const CliOutcome mpi = mpirun_closurelab(work, "run " + spec_arg + " --out " + (work / "mpi").string());
  ASSERT_EQ(mpi.code, 0) << mpi.err;
  const json a = read(work / "serial" / "rm.json"), b = read(work / "mpi" / "rm.json");
  for (const json& row : a.at("rows")) EXPECT_EQ(row.at("status"), "ok") << row.dump();
  EXPECT_EQ(without_timings(a), without_timings(b));
}

TEST(RunnerMpi, AnInvalidSpecExitsTwoOnRankZeroAndReleasesTheOthers) {
  if (!have_mpi()) GTEST_SKIP() << "built without MPI (CLOSURELAB_WITH_MPI=OFF) or no mpiexec";
  const auto work = fresh_work_folder("mpi_invalid");
  write_text(work / "bad.json", R"({"name": "bad", "kind": "direct_sph_validation",
    "base": {"scene": {"name": "poiseuille-uniform", "n_y": -4}}})");
  const CliOutcome o =
      mpirun_closurelab(work, "run " + (work / "bad.json").string() + " --out " + (work / "out").string());
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_NE(o.err.find("n_y"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(work / "out"));
}

TEST(RunnerMpi, JobsWithSeveralRanksIsRefused) {
  if (!have_mpi()) GTEST_SKIP() << "built without MPI (CLOSURELAB_WITH_MPI=OFF) or no mpiexec";
  const auto work = fresh_work_folder("mpi_jobs");
  write_text(work / "ranks.json", spec);
  const CliOutcome o = mpirun_closurelab(
      work, "run " + (work / "ranks.json").string() + " --out " + (work / "out").string() + " --jobs 2");
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_NE(o.err.find("--jobs"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(work / "out"));
}
