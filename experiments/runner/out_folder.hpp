#pragma once
// The output folder of a run: checked before anything is computed (a run that cannot write its results
// must not start), and locked while the run writes (two runs on one folder would compute every cell twice
// and race on the table).
#include <stdexcept>
#include <string>

namespace closurelab {

// Throws ConfigError (path "--out") when `dir` cannot hold a run's results: it, or `dir`/cells, exists and is
// not a folder, or it is not writable (nor creatable under its nearest existing parent). Writes nothing.
void check_output_folder(const std::string& dir);

// A lock on `dir` (flock on `dir`/`lock_name`, by default .closurelab.lock), released when the object dies or the
// process ends, also on kill -9. One lock per folder: a plain run, `merge` and `seal` hold .closurelab.lock
// exclusively; a shard of a run holds it shared (the N shards may run at once) and its own shard lock exclusively
// (shards.hpp), so a plain run and a shard never compute on one folder at once. An exclusive lock file holds the
// holder's pid, host, start date and command line (cleared when it is released).
enum class LockMode { exclusive, shared };
class FolderLock {
 public:
  // Creates `dir` if needed and takes the lock; throws FolderBusy naming the holder if another process has it
  // (for a plain run held by shards: that shards hold it), std::runtime_error if the lock file cannot be created.
  FolderLock(const std::string& dir, const std::string& command_line, const std::string& lock_name = ".closurelab.lock",
             LockMode mode = LockMode::exclusive);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
  LockMode mode_ = LockMode::exclusive;
};

struct FolderBusy : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace closurelab
