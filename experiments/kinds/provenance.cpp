#include "experiments/kinds/provenance.hpp"

#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>

#include "build_info.hpp"
#include "core/base/errors.hpp"
#include "core/sph/sph_engine.hpp"

namespace closurelab {

json provenance(const std::string& command_line) {
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  const std::time_t now = std::time(nullptr);
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  std::string commit = build_info::git_commit;
  const std::string suffix = "-dirty";
  const bool dirty = commit.size() > suffix.size() && commit.compare(commit.size() - suffix.size(), suffix.size(), suffix) == 0;
  if (dirty) commit.resize(commit.size() - suffix.size());
  return {{"git_commit", commit},
          {"dirty", dirty},
          {"version", build_info::version},
          {"compiler", build_info::compiler},
          {"cxx_flags", build_info::cxx_flags},
          {"build_type", build_info::build_type},
          {"date_utc", date},
          {"host", host},
          {"threads", omp_get_max_threads()},
          {"sph_pair_kernel", name_of(pair_kernel_isa())},  // same bits either way (SphEngineVectorKernels)
          {"command", command_line}};
}

json table_provenance(const std::vector<json>& rows) {
  std::set<std::string> commits, compilers, build_types, hosts;
  std::string first, last;
  int dirty = 0, unrecorded = 0;
  for (const json& r : rows) {
    const json p = r.value("provenance", json());
    if (!p.is_object()) {
      ++unrecorded;
      continue;
    }
    commits.insert(p.value("git_commit", "unknown"));
    compilers.insert(p.value("compiler", "unknown"));
    build_types.insert(p.value("build_type", "unknown"));
    hosts.insert(p.value("host", "unknown"));
    dirty += p.value("dirty", false) ? 1 : 0;
    const std::string d = p.value("date_utc", "");
    if (!d.empty() && (first.empty() || d < first)) first = d;
    if (!d.empty() && (last.empty() || d > last)) last = d;
  }
  return {{"derived_from", "rows"},
          {"commits", commits},
          {"dirty_rows", dirty},
          {"rows_without_provenance", unrecorded},
          {"compilers", compilers},
          {"build_types", build_types},
          {"hosts", hosts},
          {"first_date_utc", first},
          {"last_date_utc", last}};
}

double peak_memory_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

void write_file_atomically(const std::string& file, const std::string& content) {
  namespace fs = std::filesystem;
  static std::atomic<unsigned long> counter{0};
  const fs::path p(file);
  std::error_code ec;
  if (p.has_parent_path()) {
    fs::create_directories(p.parent_path(), ec);
    if (ec) throw std::runtime_error("cannot create folder '" + p.parent_path().string() + "': " + ec.message());
  }
  // Unique per process and call: two writers never share a temporary file.
  const fs::path tmp = p.string() + "." + std::to_string(getpid()) + "." + std::to_string(counter++) + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw std::runtime_error("cannot write '" + tmp.string() + "'");
    out << content;
    out.flush();
    if (!out) {
      out.close();
      fs::remove(tmp, ec);
      throw std::runtime_error("failed writing '" + tmp.string() + "'");
    }
  }
  fs::rename(tmp, p, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw std::runtime_error("cannot replace '" + p.string() + "': " + ec.message());
  }
}

}  // namespace closurelab
