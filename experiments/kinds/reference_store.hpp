#pragma once
// The persistent, shared store of direct SPH references: each entry is what a direct run determines (the final
// particle state, the snapshots at the requested times and the run's record: status, steps, cost), stored
// once under its key (a canonical JSON of everything that determines it: scene, averaging kernel and mesh of
// the steady test, SPH solver options, snapshot times, the engine version core/sph/engine_version.hpp) and
// reused by every cell and spec, in this process and later ones.
//
// Layout: DIR/<id>/ with id = 16 hex digits of the 64-bit FNV-1a hash of the key's canonical dump (keys
// sorted); inside, particles.h5part (the snapshots, then the final state: H5Part layout, core/io/h5part.hpp)
// and entry.json (the full key, compared on read, so a hash collision is harmless; the run's record; the
// payload's size and FNV-1a checksum; the provenance of the run that computed it; a checksum of all of these, so
// an edited status or step count is not reused). Only folders named by 16 hex digits are entries.
// Safety: an entry is written to a temporary folder DIR/.tmp-<id>-... and renamed, so a half-written entry is
// never visible; on read the key, the payload's size and checksum and the HDF5 contents are checked, and a
// corrupt or truncated entry is reported on stderr, removed and recomputed. Cross-process (and cross-thread):
// a lock file DIR/<id>.lock (flock) is held while an entry is read or computed, so two cells or processes
// needing the same reference compute it once (the second waits, then reads it). A store that cannot be written
// (a shared precomputed store on a read-only mount) is read without the lock, and an entry missing there is
// computed and not stored, with a note. Temporaries of writers that died are not counted, and removed by the
// next write once an hour old.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "core/base/params.hpp"
#include "core/io/particle_snapshot.hpp"

namespace closurelab {

struct StoredReference {
  std::vector<ParticleSnapshot> snapshots;  // at the requested times, in order (a run may end before some)
  ParticleSystem particles;                 // the final state
  json run;                                 // the run's record (SphRunResult::to_json())
  // Set by the store: {"entry": id, "reused": bool, "computed_by": provenance of the computing run}.
  json store;
};

struct StoreEntryInfo {
  std::string id;
  std::uintmax_t bytes = 0;
  json key;              // null when unreadable
  std::string problem;   // empty when the entry's metadata reads; else why not (the payload is not checked)
  std::string computed;  // UTC date of the computing run
  std::string status;    // the run's status (converged, target_time, no_convergence, numerical_issue)
};

class ReferenceStore {
 public:
  // `force`: each entry is recomputed the first time this process asks for it, then reused.
  explicit ReferenceStore(std::filesystem::path dir, bool force = false);

  // The stored entry under `key` when present and intact, else compute() (under the entry's lock), stored.
  StoredReference get_or_compute(const json& key, const std::function<StoredReference()>& compute);

  std::vector<StoreEntryInfo> list() const;
  std::uintmax_t total_bytes() const;  // every file under the folder (entries, temporaries, locks)
  const std::filesystem::path& dir() const { return dir_; }
  bool force() const { return force_; }

 private:
  bool try_read(const std::string& id, const json& key, StoredReference& out) const;
  void write(const std::string& id, const json& key, const StoredReference& ref) const;

  std::filesystem::path dir_;
  bool force_ = false;
  std::mutex refreshed_mutex_;
  std::set<std::string> refreshed_;  // ids recomputed by this process under `force`
};

// 64-bit FNV-1a of a byte string, and of a file's contents (std::runtime_error when unreadable).
std::uint64_t fnv1a64(const std::string& bytes);
std::uint64_t fnv1a64_file(const std::filesystem::path& file);
// 16 lowercase hex digits of fnv1a64(bytes) (the store's ids and checksums, the runner's cell ids and cell files).
std::string fnv1a64_hex(const std::string& bytes);
// The entry id of a key: 16 lowercase hex digits of fnv1a64(key.dump()) (nlohmann's dump sorts keys).
std::string store_entry_id(const json& key);

// The default folder: $CLOSURELAB_STORE when set and not empty, else $HOME/.cache/closurelab/store (else
// .closurelab-store in the working folder when HOME is unset).
std::string default_reference_store_dir();
// The process-wide store used by the experiment kinds; `configure_reference_store` (the command line's
// --store and --force) replaces it; before any call, the default folder without force.
ReferenceStore& reference_store();
void configure_reference_store(const std::string& dir, bool force);

}  // namespace closurelab
