// The reference store (experiments/kinds/reference_store.hpp) and the particle files under it
// (core/io/h5part.hpp, core/io/particle_snapshot.hpp): exact round trips, a stored entry reused by a second
// store object (as by a later process), a corrupt or truncated entry detected, reported, removed and
// recomputed, a changed key computing a new entry, --force recomputing once, and two threads needing the same
// entry computing it once (separate lock descriptors exclude each other as two processes' do).
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <thread>

#include "core/base/errors.hpp"
#include "core/io/h5part.hpp"
#include "core/io/particle_snapshot.hpp"
#include "core/sph/sph_run.hpp"
#include "experiments/kinds/reference_store.hpp"

using namespace closurelab;
namespace fs = std::filesystem;

namespace {

fs::path fresh(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("closurelab_store_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

ParticleSystem sample_particles(int n, double shift) {
  ParticleSystem p;
  for (int k = 0; k < n; ++k) {
    p.add(0.1 * k + shift, 1.0 / 3.0 + k, 0.7 + k, k % 3, k % 2 == 0);
    p.vx.back() = std::sin(k + shift);
    p.vy.back() = -1e-300 * k;  // subnormal-range values survive too
  }
  return p;
}

void expect_same(const ParticleSystem& a, const ParticleSystem& b) {
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.vx, b.vx);
  EXPECT_EQ(a.vy, b.vy);
  EXPECT_EQ(a.mass, b.mass);
  EXPECT_EQ(a.phase, b.phase);
  EXPECT_EQ(a.fixed, b.fixed);
}

StoredReference sample_reference(double shift) {
  StoredReference r;
  r.snapshots.push_back({0.25, sample_particles(5, shift), true});
  r.particles = sample_particles(7, shift + 1);
  r.run = {{"status", "converged"}, {"time", 0.5}, {"steps", 12}};
  return r;
}

const json key_a = {{"kind", "test"}, {"scene", {{"name", "a"}, {"n_y", 16}}}};

}  // namespace

TEST(Fnv1a64, KnownValues) {
  // The published FNV-1a 64-bit test vectors (offset basis for the empty string).
  EXPECT_EQ(fnv1a64(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(fnv1a64("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(fnv1a64("foobar"), 0x85944171f73967e8ull);
  EXPECT_EQ(store_entry_id(json{{"b", 1}, {"a", 2}}), store_entry_id(json{{"a", 2}, {"b", 1}}));  // canonical
}

TEST(H5Part, RoundTripIsExactAndKeepsTheLayout) {
  const fs::path dir = fresh("h5");
  const std::string file = (dir / "p.h5part").string();
  write_h5part(file, {{0.0, sample_particles(4, 0.0), true}, {1.5, sample_particles(6, 2.0), true}});
  EXPECT_EQ(h5part_step_count(file), 2);
  const std::vector<ParticleSnapshot> all = read_h5part_all(file);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[1].time, 1.5);
  EXPECT_TRUE(all[1].has_fixed);
  expect_same(all[0].particles, sample_particles(4, 0.0));
  expect_same(read_particle_snapshot(file).particles, sample_particles(6, 2.0));  // -1: the last step
  EXPECT_THROW(read_h5part(file, 2), ConfigError);
}

TEST(H5Part, TruncatedOrForeignFilesAreConfigErrors) {
  const fs::path dir = fresh("h5bad");
  const std::string file = (dir / "p.h5part").string();
  write_h5part(file, {{0.0, sample_particles(200, 0.0), true}});
  fs::resize_file(file, fs::file_size(file) / 2);
  EXPECT_THROW(read_h5part(file), ConfigError);
  std::ofstream(dir / "text.h5part") << "not hdf5\n";
  EXPECT_THROW(read_h5part((dir / "text.h5part").string()), ConfigError);
  EXPECT_THROW(read_h5part((dir / "missing.h5part").string()), ConfigError);
  EXPECT_THROW(read_particle_snapshot((dir / "p.vtk").string()), ConfigError);
}

TEST(ParticleCsv, ReadsAnyColumnOrderAndRefusesBadLines) {
  const fs::path dir = fresh("csv");
  std::ofstream(dir / "ok.csv") << "# from another code\nphase,mass,vy,vx,y,x,extra\n0,2.5,0,1.25,0.5,0.25,x\n1,2.5,0,-1,0.75,0.5,y\n";
  const ParticleSnapshot s = read_particle_csv((dir / "ok.csv").string());
  ASSERT_EQ(s.particles.size(), 2u);
  EXPECT_FALSE(s.has_fixed);
  EXPECT_EQ(s.particles.x[0], 0.25);
  EXPECT_EQ(s.particles.vx[0], 1.25);
  EXPECT_EQ(s.particles.phase[1], 1);
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"x,y,vx,vy,mass\n0,0,0,0,1\n", "phase"},
      {"x,y,vx,vy,mass,phase\n0,0,0,zero,1,0\n", "'zero'"},
      {"x,y,vx,vy,mass,phase\n0,0,0,0,1\n", "5 fields"},
      {"x,y,vx,vy,mass,phase\n0,0,0,0,-1,0\n", "mass"},
      {"x,y,vx,vy,mass,phase\n0,0,nan,0,1,0\n", "non-finite"},
      {"x,y,vx,vy,mass,phase\n0,0,0,0,1,0.5\n", "phase"},
      {"x,y,vx,vy,mass,phase,vx\n0,0,0,0,1,0,1\n", "column 'vx' twice"},
      {"", "empty"}};
  for (const auto& [text, fragment] : bad) {
    std::ofstream(dir / "bad.csv") << text;
    try {
      read_particle_csv((dir / "bad.csv").string());
      ADD_FAILURE() << "accepted: " << text;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  }
}

TEST(ReferenceStore, StoresOnceAndALaterStoreObjectReusesTheEntry) {
  const fs::path dir = fresh("reuse");
  int computed = 0;
  const auto compute = [&] { return ++computed, sample_reference(0.0); };
  ReferenceStore store(dir);
  const StoredReference first = store.get_or_compute(key_a, compute);
  EXPECT_FALSE(first.store.at("reused").get<bool>());
  const StoredReference second = ReferenceStore(dir).get_or_compute(key_a, compute);
  EXPECT_EQ(computed, 1);
  EXPECT_TRUE(second.store.at("reused").get<bool>());
  EXPECT_EQ(second.store.at("entry"), store_entry_id(key_a));
  EXPECT_EQ(second.run, first.run);
  expect_same(second.particles, first.particles);
  ASSERT_EQ(second.snapshots.size(), 1u);
  EXPECT_EQ(second.snapshots[0].time, 0.25);
  expect_same(second.snapshots[0].particles, first.snapshots[0].particles);
  // The payload opens as a plain H5Part file: snapshots, then the final state.
  EXPECT_EQ(h5part_step_count((dir / store_entry_id(key_a) / "particles.h5part").string()), 2);
  const auto entries = store.list();
  ASSERT_EQ(entries.size(), 1u);
  EXPECT_EQ(entries[0].key, key_a);
  EXPECT_EQ(entries[0].status, "converged");
  EXPECT_GT(entries[0].bytes, 0u);
  EXPECT_GE(store.total_bytes(), entries[0].bytes);
  for (const auto& e : fs::directory_iterator(dir))  // no temporary left behind
    EXPECT_NE(e.path().filename().string().rfind(".tmp-", 0), 0u) << e.path();
}

TEST(ReferenceStore, ACorruptOrTruncatedEntryIsReportedRemovedAndRecomputed) {
  const fs::path dir = fresh("corrupt");
  int computed = 0;
  const auto compute = [&] { return ++computed, sample_reference(0.0); };
  const fs::path entry = dir / store_entry_id(key_a);
  const fs::path payload = entry / "particles.h5part";
  const std::vector<std::pair<std::string, std::function<void()>>> damages = {
      {"one flipped payload byte", [&] {
         std::fstream f(payload, std::ios::in | std::ios::out | std::ios::binary);
         f.seekg(static_cast<std::streamoff>(fs::file_size(payload) - 40));
         const char c = static_cast<char>(f.get());
         f.seekp(static_cast<std::streamoff>(fs::file_size(payload) - 40));
         f.put(static_cast<char>(c ^ 0x5a));
       }},
      {"a truncated payload", [&] { fs::resize_file(payload, fs::file_size(payload) / 2); }},
      {"a truncated entry.json", [&] { fs::resize_file(entry / "entry.json", 20); }},
      {"a missing payload", [&] { fs::remove(payload); }},
      {"an empty entry folder", [&] { fs::remove_all(entry), fs::create_directories(entry); }}};
  ReferenceStore(dir).get_or_compute(key_a, compute);
  for (const auto& [what, damage] : damages) {
    const int before = computed;
    damage();
    ::testing::internal::CaptureStderr();
    const StoredReference r = ReferenceStore(dir).get_or_compute(key_a, compute);
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(computed, before + 1) << what;  // recomputed, never used
    EXPECT_FALSE(r.store.at("reused").get<bool>()) << what;
    EXPECT_NE(err.find("not usable"), std::string::npos) << what << ": " << err;
    expect_same(r.particles, sample_reference(0.0).particles);
    EXPECT_TRUE(ReferenceStore(dir).get_or_compute(key_a, compute).store.at("reused").get<bool>()) << what;
  }
}

TEST(ReferenceStore, AChangedKeyComputesANewEntryAndForceRecomputesOnce) {
  const fs::path dir = fresh("key");
  int computed = 0;
  const auto compute = [&] { return ++computed, sample_reference(computed); };
  ReferenceStore(dir).get_or_compute(key_a, compute);
  json key_b = key_a;
  key_b["scene"]["n_y"] = 32;
  EXPECT_FALSE(ReferenceStore(dir).get_or_compute(key_b, compute).store.at("reused").get<bool>());
  EXPECT_EQ(computed, 2);
  EXPECT_EQ(ReferenceStore(dir).list().size(), 2u);
  ReferenceStore forced(dir, true);
  EXPECT_FALSE(forced.get_or_compute(key_a, compute).store.at("reused").get<bool>());
  EXPECT_EQ(computed, 3);
  EXPECT_TRUE(forced.get_or_compute(key_a, compute).store.at("reused").get<bool>());  // once per process
  EXPECT_EQ(computed, 3);
}

TEST(ReferenceStore, TwoThreadsNeedingTheSameEntryComputeItOnce) {
  const fs::path dir = fresh("threads");
  std::atomic<int> computed{0};
  const auto compute = [&] {
    ++computed;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));  // lets the other thread arrive meanwhile
    return sample_reference(0.0);
  };
  ReferenceStore store(dir);
  StoredReference r1, r2;
  ::testing::internal::CaptureStderr();
  std::thread t1([&] { r1 = store.get_or_compute(key_a, compute); });
  std::thread t2([&] { r2 = ReferenceStore(dir).get_or_compute(key_a, compute); });
  t1.join();
  t2.join();
  ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(computed.load(), 1);
  EXPECT_NE(r1.store.at("reused").get<bool>(), r2.store.at("reused").get<bool>());
}

TEST(SphRunResult, JsonRoundTrip) {
  SphRunResult r;
  r.status = Status::no_convergence;
  r.steps = 123456789012;
  r.time = 0.1;
  r.dt = 1.0 / 3.0;
  r.wall_seconds = 2.5;
  r.last_relative_change = 1e-7;
  r.moving_particles = 5;
  r.active_particles = 6;
  r.total_particles = 7;
  r.pair_evaluations = 8;
  r.list_rebuilds = 9;
  r.message = "why";
  EXPECT_EQ(SphRunResult::from_json(r.to_json()).to_json(), r.to_json());
}
