#pragma once
// Shared by the command-line integration tests: runs the closurelab executable in a shell and captures its
// exit code, stdout and stderr; one work folder per test process (ctest runs the cases in parallel processes).
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace closurelab::testing {

struct CliOutcome {
  int code;
  std::string out, err;
};

inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline void write_text(const std::filesystem::path& p, const std::string& text) {
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

// A folder of this test process, removed and recreated by each call.
inline std::filesystem::path fresh_work_folder(const std::string& name) {
  const auto p = std::filesystem::temp_directory_path() / ("closurelab_" + name + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p);
  return p;
}

// Runs `command` (a shell command line) with stdout and stderr captured in files under `work`.
inline CliOutcome run_shell(const std::filesystem::path& work, const std::string& command) {
  const auto out = work / "stdout.txt", err = work / "stderr.txt";
  const int status = std::system((command + " >" + out.string() + " 2>" + err.string()).c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), read_text(out), read_text(err)};
}

// Runs `closurelab ARGS`.
inline CliOutcome run_closurelab(const std::filesystem::path& work, const std::string& args) {
  return run_shell(work, std::string(CLOSURELAB_BINARY_DIR) + "/experiments/closurelab " + args);
}

}  // namespace closurelab::testing
