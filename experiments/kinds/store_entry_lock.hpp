#pragma once
// The reference store's per-entry lock (experiments/kinds/reference_store.cpp): an exclusive flock on
// DIR/<id>.lock, opened without following links.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>

namespace closurelab {

// An exclusive flock on DIR/<id>.lock for the lifetime of the object. Locks of separate open() calls
// exclude each other, between threads of one process as between processes; the kernel drops the lock of a
// process that dies. The lock files stay (removing one would race with a process about to lock it).
// A store on a read-only mount (a shared precomputed store) cannot take the lock: `read_only()` says so, and the
// store reads without it (an entry appears by one rename, so a reader sees a whole entry or none).
class EntryLock {
 public:
  EntryLock(const std::filesystem::path& file, const std::string& id) {
    fd_ = ::open(file.c_str(), O_CREAT | O_RDWR | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd_ < 0 && (errno == EROFS || errno == EACCES || errno == EPERM)) {
      fd_ = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);  // an existing lock file: a shared lock works
      if (fd_ < 0) {
        read_only_ = true;
        return;
      }
    }
    if (fd_ < 0) throw std::runtime_error("reference store: cannot open lock file '" + file.string() + "': " + std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) return;
    std::cerr << "reference store: entry " << id << " is being computed by another cell or process; waiting\n";
    while (::flock(fd_, LOCK_EX) != 0)
      if (errno != EINTR) {
        ::close(fd_);
        throw std::runtime_error("reference store: cannot lock '" + file.string() + "': " + std::strerror(errno));
      }
  }
  EntryLock(const EntryLock&) = delete;
  EntryLock& operator=(const EntryLock&) = delete;
  ~EntryLock() {
    if (fd_ < 0) return;
    ::flock(fd_, LOCK_UN);
    ::close(fd_);
  }
  bool read_only() const { return read_only_; }

 private:
  int fd_ = -1;
  bool read_only_ = false;
};

}  // namespace closurelab
