#include "experiments/runner/out_folder.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>

#include "core/base/errors.hpp"

namespace closurelab {

namespace fs = std::filesystem;

void check_output_folder(const std::string& dir) {
  if (dir.empty()) throw ConfigError("--out", "needs a folder name, got ''");
  const fs::path out(dir);
  std::error_code ec;
  if (fs::exists(out, ec)) {
    if (!fs::is_directory(out, ec)) throw ConfigError("--out", "'" + dir + "' exists and is not a folder");
    const fs::path cells = out / "cells";
    if (fs::exists(cells, ec) && !fs::is_directory(cells, ec))
      throw ConfigError("--out", "'" + cells.string() + "' exists and is not a folder (it holds the finished cells)");
    if (access(out.c_str(), W_OK | X_OK) != 0)
      throw ConfigError("--out", "folder '" + dir + "' is not writable: " + std::strerror(errno));
    if (fs::exists(cells, ec) && access(cells.c_str(), W_OK | X_OK) != 0)
      throw ConfigError("--out", "folder '" + cells.string() + "' is not writable: " + std::strerror(errno));
    return;
  }
  // Not there yet: the nearest existing ancestor must be a writable folder.
  fs::path parent = fs::absolute(out, ec).parent_path();
  while (!parent.empty() && !fs::exists(parent, ec) && parent != parent.root_path()) parent = parent.parent_path();
  if (!fs::is_directory(parent, ec))
    throw ConfigError("--out", "cannot create '" + dir + "': '" + parent.string() + "' is not a folder");
  if (access(parent.c_str(), W_OK | X_OK) != 0)
    throw ConfigError("--out", "cannot create '" + dir + "': '" + parent.string() + "' is not writable: " + std::strerror(errno));
}

FolderLock::FolderLock(const std::string& dir, const std::string& command_line, const std::string& lock_name,
                       LockMode mode)
    : mode_(mode) {
  std::error_code ec;
  fs::create_directories(fs::path(dir) / "cells", ec);
  if (ec) throw std::runtime_error("cannot create folder '" + (fs::path(dir) / "cells").string() + "': " + ec.message());
  const fs::path file = fs::path(dir) / lock_name;
  // Never through a link: a symbolic link planted at the lock's name would otherwise have its target truncated
  // and overwritten with the holder's note (the store's locks and the table's rename behave the same way).
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
  if (fd_ < 0) {
    const int err = errno;
    if (err == ELOOP)
      throw std::runtime_error("the lock file '" + file.string() +
                               "' is a symbolic link; it is not followed (remove it, or use another --out)");
    throw std::runtime_error("cannot create the lock file '" + file.string() + "': " + std::strerror(err));
  }
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    fd_ = -1;
    throw std::runtime_error("the lock file '" + file.string() + "' is not a regular file (remove it, or use another --out)");
  }
  if (::flock(fd_, (mode == LockMode::shared ? LOCK_SH : LOCK_EX) | LOCK_NB) != 0) {
    // Held shared: by shards (their notes are in their own lock files); held exclusively: the note says by whom.
    const bool by_shards = mode == LockMode::exclusive && ::flock(fd_, LOCK_SH | LOCK_NB) == 0;
    char buf[1024] = {0};
    const ssize_t n = by_shards ? 0 : ::pread(fd_, buf, sizeof buf - 1, 0);
    std::string holder = by_shards ? "shards of a run (--shard; their lock files are " + dir + "/.closurelab.shard-*.lock)"
                         : n > 0   ? std::string(buf, static_cast<std::size_t>(n))
                                   : "an unknown process";
    while (!holder.empty() && holder.back() == '\n') holder.pop_back();
    ::close(fd_);
    fd_ = -1;
    throw FolderBusy("folder '" + dir + "' is in use by another run (" + holder + "); wait for it to finish or use another --out");
  }
  if (mode == LockMode::shared) return;  // several holders: no one note
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  const std::time_t now = std::time(nullptr);
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  const std::string who = "pid " + std::to_string(getpid()) + " on " + host + " since " + date + ": " + command_line + "\n";
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, who.data(), who.size(), 0) < 0) {
    // The lock holds without the note; the message of a second run is then less specific.
  }
}

FolderLock::~FolderLock() {
  if (fd_ >= 0 && mode_ == LockMode::exclusive && ::ftruncate(fd_, 0) != 0) {
    // The note stays; it names a run that is over, and the lock is free.
  }
  if (fd_ >= 0) ::close(fd_);  // closing releases the flock
}

}  // namespace closurelab
