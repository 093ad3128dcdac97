#include "experiments/kinds/reference_store.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "core/base/json_reader.hpp"
#include "core/io/h5part.hpp"
#include "experiments/kinds/store_entry_lock.hpp"
#include "experiments/kinds/provenance.hpp"

namespace closurelab {

namespace fs = std::filesystem;

namespace {

constexpr std::uint64_t fnv_offset = 14695981039346656037ull, fnv_prime = 1099511628211ull;
const char* const payload_name = "particles.h5part";
const char* const entry_name = "entry.json";
// Format 2: the metadata (key, run record, payload size and checksum, provenance) is inside a checksum of its
// own, so an edited status or step count is not reused; format-1 entries had none and are recomputed.
constexpr int entry_format = 2;
// A temporary folder older than this belongs to a writer that died (an entry is written in seconds, after the
// run): it is removed and never counted.
constexpr auto stale_temporary_age = std::chrono::hours(1);

std::string hex16(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

// The checksum of an entry's metadata: the FNV-1a of its dump without the checksum itself.
std::string meta_checksum(json meta) {
  meta.erase("meta_fnv1a64");
  return hex16(fnv1a64(meta.dump()));
}

// An entry's folder name: 16 lowercase hex digits (store_entry_id); anything else in the store (a lock file
// that is a folder, a run's cells/ folder put there by mistake, temporaries) is not an entry.
bool is_entry_name(const std::string& name) {
  return name.size() == 16 && std::all_of(name.begin(), name.end(), [](char c) {
           return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
         });
}

bool is_temporary_name(const std::string& name) { return name.rfind(".tmp-", 0) == 0; }

bool is_stale(const fs::path& p) {
  std::error_code ec;
  const auto t = fs::last_write_time(p, ec);
  return !ec && fs::file_time_type::clock::now() - t > stale_temporary_age;
}

void sync_path(const fs::path& p) {
  const int fd = ::open(p.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

std::uintmax_t folder_bytes(const fs::path& dir) {
  std::uintmax_t total = 0;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    std::error_code e2;
    if (it.depth() == 0 && is_temporary_name(it->path().filename().string())) {  // a writer's, not the store's
      it.disable_recursion_pending();
      continue;
    }
    if (it->is_regular_file(e2)) total += it->file_size(e2);
  }
  return total;
}

}  // namespace

std::uint64_t fnv1a64(const std::string& bytes) {
  std::uint64_t h = fnv_offset;
  for (unsigned char c : bytes) h = (h ^ c) * fnv_prime;
  return h;
}

std::uint64_t fnv1a64_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read '" + file.string() + "'");
  std::uint64_t h = fnv_offset;
  std::vector<char> buf(1 << 20);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    for (std::streamsize k = 0; k < in.gcount(); ++k) h = (h ^ static_cast<unsigned char>(buf[k])) * fnv_prime;
  }
  if (in.bad()) throw std::runtime_error("cannot read '" + file.string() + "'");
  return h;
}

std::string fnv1a64_hex(const std::string& bytes) { return hex16(fnv1a64(bytes)); }

std::string store_entry_id(const json& key) { return fnv1a64_hex(key.dump()); }

ReferenceStore::ReferenceStore(fs::path dir, bool force) : dir_(std::move(dir)), force_(force) {}

bool ReferenceStore::try_read(const std::string& id, const json& key, StoredReference& out) const {
  const fs::path entry = dir_ / id;
  std::error_code ec;
  if (!fs::exists(entry / entry_name, ec) && !fs::exists(entry, ec)) return false;
  std::string problem;
  try {
    const json meta = read_json_file_guarded((entry / entry_name).string());
    const int format = meta.value("format", 0);
    if (format == 1) throw std::runtime_error("written by an older closurelab (format 1: no checksum of its run record)");
    if (format != entry_format) throw std::runtime_error("unknown entry format");
    if (meta_checksum(meta) != meta.value("meta_fnv1a64", "")) {
      problem = "its entry.json does not match its checksum (edited?)";
    } else if (meta.at("key") != key) {
      problem = "it holds another key (a hash collision)";
    } else {
      const fs::path payload = entry / payload_name;
      const json& p = meta.at("payload");
      if (fs::file_size(payload) != p.at("bytes").get<std::uintmax_t>())
        problem = "the payload has " + std::to_string(fs::file_size(payload)) + " bytes, the entry says " +
                  std::to_string(p.at("bytes").get<std::uintmax_t>()) + " (truncated?)";
      else if (hex16(fnv1a64_file(payload)) != p.at("fnv1a64").get<std::string>())
        problem = "the payload's checksum does not match (corrupt)";
      else {
        std::vector<ParticleSnapshot> steps = read_h5part_all(payload.string());
        const std::size_t n = meta.at("snapshot_count").get<std::size_t>();
        if (steps.size() != n + 1) throw std::runtime_error("the payload has " + std::to_string(steps.size()) + " steps");
        out.particles = std::move(steps.back().particles);
        steps.pop_back();
        out.snapshots = std::move(steps);
        out.run = meta.at("run");
        out.store = {{"entry", id}, {"reused", true}, {"computed_by", meta.at("computed_by")}};
        return true;
      }
    }
  } catch (const std::exception& e) {
    problem = std::string("it cannot be read: ") + e.what();
  }
  std::cerr << "reference store: entry " << entry.string() << " is not usable (" << problem
            << "); removing it and recomputing\n";
  fs::remove_all(entry, ec);  // fails harmlessly on a read-only store
  return false;
}

void ReferenceStore::write(const std::string& id, const json& key, const StoredReference& ref) const {
  static std::atomic<long> counter{0};
  // Leftovers of an interrupted write of this entry (we hold its lock: nobody else is writing it).
  std::error_code ec;
  // Those of dead writers of other entries too (older than stale_temporary_age).
  for (const auto& e : fs::directory_iterator(dir_, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(".tmp-" + id + "-", 0) == 0 || (is_temporary_name(name) && is_stale(e.path())))
      fs::remove_all(e.path(), ec);
  }
  const fs::path tmp = dir_ / (".tmp-" + id + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  try {
    fs::create_directories(tmp);
    std::vector<ParticleSnapshot> steps = ref.snapshots;
    steps.push_back({ref.run.value("time", 0.0), ref.particles, true});
    write_h5part((tmp / payload_name).string(), steps);
    sync_path(tmp / payload_name);
    json computed_by = ref.store.value("computed_by", json::object());
    json meta = {{"format", entry_format},
                 {"key", key},
                 {"run", ref.run},
                 {"snapshot_count", ref.snapshots.size()},
                 {"payload", {{"file", payload_name},
                              {"bytes", fs::file_size(tmp / payload_name)},
                              {"fnv1a64", hex16(fnv1a64_file(tmp / payload_name))}}},
                 {"computed_by", computed_by}};
    meta["meta_fnv1a64"] = meta_checksum(meta);
    {
      std::ofstream out(tmp / entry_name, std::ios::binary);
      out << meta.dump(1) << "\n";
      out.flush();
      if (!out) throw std::runtime_error("cannot write '" + (tmp / entry_name).string() + "'");
    }
    sync_path(tmp / entry_name);
    sync_path(tmp);
    fs::remove_all(dir_ / id);  // an entry found corrupt, or recomputed under force
    fs::rename(tmp, dir_ / id);
    sync_path(dir_);
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
}

StoredReference ReferenceStore::get_or_compute(const json& key, const std::function<StoredReference()>& compute) {
  const std::string id = store_entry_id(key);
  std::error_code ec;
  if (!fs::is_directory(dir_, ec) && !fs::create_directories(dir_, ec)) {
    std::cerr << "reference store: cannot create the folder '" << dir_.string() << "': " << ec.message()
              << "; computing without the store\n";
    StoredReference ref = compute();
    ref.store = {{"entry", id}, {"reused", false}, {"stored", false}};
    return ref;
  }
  EntryLock lock(dir_ / (id + ".lock"), id);
  if (lock.read_only()) {
    std::cerr << "reference store: '" << dir_.string() << "' is read-only; reading entry " << id
              << " without its lock" << (force_ ? " (--force cannot recompute into it)" : "") << "\n";
    StoredReference ref;
    if (!force_ && try_read(id, key, ref)) return ref;
    std::cerr << "reference store: entry " << id << " is not in the read-only store; computing it, not stored\n";
    ref = compute();
    ref.store = {{"entry", id}, {"reused", false}, {"stored", false}};
    return ref;
  }
  bool recompute = false;
  if (force_) {
    std::lock_guard<std::mutex> g(refreshed_mutex_);
    recompute = refreshed_.insert(id).second;
  }
  StoredReference ref;
  if (!recompute && try_read(id, key, ref)) return ref;
  ref = compute();
  json computed_by = provenance("");
  computed_by.erase("command");
  ref.store = {{"entry", id}, {"reused", false}, {"computed_by", computed_by}};
  try {
    write(id, key, ref);
  } catch (const std::exception& e) {  // the result stands; only its reuse is lost
    std::cerr << "reference store: cannot store entry " << id << " in '" << dir_.string() << "': " << e.what()
              << "; the result is used but not stored\n";
    ref.store["stored"] = false;
  }
  return ref;
}

std::vector<StoreEntryInfo> ReferenceStore::list() const {
  std::vector<StoreEntryInfo> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir_, ec)) {
    const std::string name = e.path().filename().string();
    std::error_code e2;
    if (!is_entry_name(name) || !e.is_directory(e2) || e.is_symlink(e2)) continue;
    StoreEntryInfo info;
    info.id = name;
    info.bytes = folder_bytes(e.path());
    try {
      const json meta = read_json_file_guarded((e.path() / entry_name).string());
      info.key = meta.at("key");
      info.computed = meta.at("computed_by").value("date_utc", "");
      info.status = meta.at("run").value("status", "");
    } catch (const std::exception& ex) {
      info.problem = ex.what();
    }
    out.push_back(std::move(info));
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  return out;
}

std::uintmax_t ReferenceStore::total_bytes() const { return folder_bytes(dir_); }

std::string default_reference_store_dir() {
  if (const char* s = std::getenv("CLOSURELAB_STORE"); s && *s) return s;
  if (const char* h = std::getenv("HOME"); h && *h) return (fs::path(h) / ".cache" / "closurelab" / "store").string();
  return ".closurelab-store";
}

namespace {
std::mutex store_mutex;
std::unique_ptr<ReferenceStore> store;
}  // namespace

ReferenceStore& reference_store() {
  std::lock_guard<std::mutex> g(store_mutex);
  if (!store) store = std::make_unique<ReferenceStore>(default_reference_store_dir());
  return *store;
}

void configure_reference_store(const std::string& dir, bool force) {
  std::lock_guard<std::mutex> g(store_mutex);
  store = std::make_unique<ReferenceStore>(dir, force);
}

}  // namespace closurelab
