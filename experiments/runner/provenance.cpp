#include "experiments/runner/provenance.hpp"

#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>

#include "build_info.hpp"
#include "core/base/errors.hpp"

namespace closurelab {

json provenance(const std::string& command_line) {
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  const std::time_t now = std::time(nullptr);
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return {{"git_commit", build_info::git_commit},
          {"version", build_info::version},
          {"compiler", build_info::compiler},
          {"cxx_flags", build_info::cxx_flags},
          {"build_type", build_info::build_type},
          {"date_utc", date},
          {"host", host},
          {"threads", omp_get_max_threads()},
          {"command", command_line}};
}

double peak_memory_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

void write_file_atomically(const std::string& file, const std::string& content) {
  namespace fs = std::filesystem;
  const fs::path p(file);
  if (p.has_parent_path()) fs::create_directories(p.parent_path());
  const fs::path tmp = p.string() + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw ConfigError("", "cannot write '" + tmp.string() + "'");
    out << content;
    if (!out) throw ConfigError("", "failed writing '" + tmp.string() + "'");
  }
  fs::rename(tmp, p);
}

}  // namespace closurelab
