// The reference store's metadata and folder hygiene: an edited run record (status, steps) or an entry
// of the old format without its checksum is not reused; `list` and the size count only entries (16 hex digits),
// not a lock that is a folder, a cells/ folder or a writer's temporaries; a temporary over an hour old is removed
// by the next write, a recent one is not.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/base/json_reader.hpp"
#include "experiments/kinds/reference_store.hpp"

using namespace closurelab;
namespace fs = std::filesystem;

namespace {

fs::path fresh(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("closurelab_store_safety_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

StoredReference sample() {
  StoredReference r;
  ParticleSystem p;
  for (int k = 0; k < 4; ++k) p.add(0.1 * k, 0.2 * k, 1.0, 0, k == 0);
  r.particles = p;
  r.run = {{"status", "no_convergence"}, {"time", 0.5}, {"steps", 12}};
  return r;
}

const json key = {{"kind", "test"}, {"scene", {{"name", "a"}}}};

void edit_entry(const fs::path& file, const std::function<void(json&)>& edit) {
  json meta = read_json_file_guarded(file.string());
  edit(meta);
  std::ofstream(file, std::ios::trunc) << meta.dump(1) << "\n";
}

}  // namespace

TEST(ReferenceStoreSafety, AnEditedRunRecordOrAnOldFormatIsNotReused) {
  const fs::path dir = fresh("edit");
  int computed = 0;
  const auto compute = [&] { return ++computed, sample(); };
  ReferenceStore(dir).get_or_compute(key, compute);
  const fs::path entry_json = dir / store_entry_id(key) / "entry.json";
  const std::vector<std::pair<std::string, std::function<void(json&)>>> edits = {
      {"status edited", [](json& m) { m["run"]["status"] = "converged"; }},
      {"steps: -5", [](json& m) { m["run"]["steps"] = -5; }},
      {"old format", [](json& m) { m["format"] = 1, m.erase("meta_fnv1a64"); }}};
  for (const auto& [what, edit] : edits) {
    const int before = computed;
    edit_entry(entry_json, edit);
    ::testing::internal::CaptureStderr();
    const StoredReference r = ReferenceStore(dir).get_or_compute(key, compute);
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(computed, before + 1) << what;
    EXPECT_EQ(r.run.at("status"), "no_convergence") << what;
    EXPECT_EQ(r.run.at("steps"), 12) << what;
    EXPECT_NE(err.find("not usable"), std::string::npos) << what << ": " << err;
  }
  EXPECT_TRUE(ReferenceStore(dir).get_or_compute(key, compute).store.at("reused").get<bool>());
}

TEST(ReferenceStoreSafety, OnlyEntriesAreListedAndCounted) {
  const fs::path dir = fresh("list");
  ReferenceStore store(dir);
  store.get_or_compute(key, [] { return sample(); });
  const std::uintmax_t bytes = store.total_bytes();
  fs::create_directories(dir / "0123456789abcdef.lock");  // a lock that is a folder
  fs::create_directories(dir / "cells");
  std::ofstream(dir / "cells" / "x.json") << "{}";
  const fs::path dead = dir / ".tmp-0123456789abcdef-999999-0", live = dir / ".tmp-fedcba9876543210-1-0";
  for (const fs::path& t : {dead, live}) {
    fs::create_directories(t);
    std::ofstream(t / "particles.h5part") << std::string(4096, 'x');
  }
  fs::last_write_time(dead, fs::file_time_type::clock::now() - std::chrono::hours(2));
  const auto entries = store.list();
  ASSERT_EQ(entries.size(), 1u);
  EXPECT_EQ(entries[0].id, store_entry_id(key));
  EXPECT_EQ(store.total_bytes(), bytes + 2);  // the cells/x.json; no temporaries
  // The next write removes the dead writer's temporary (two hours old), not the recent one.
  json other = key;
  other["scene"]["name"] = "b";
  store.get_or_compute(other, [] { return sample(); });
  EXPECT_FALSE(fs::exists(dead));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_EQ(store.list().size(), 2u);
}
