// A truncated H5Part file: refused with one message naming the file and its declared size, before
// HDF5 opens it (HDF5 1.10 leaked the file's identifiers on that path and printed "infinite loop closing
// library" and ~500 E,E,E at exit). Run through the command line, since the noise came at process exit.
#include <gtest/gtest.h>

#include "core/base/params.hpp"
#include "core/io/h5part.hpp"
#include "tests/support/cli_run.hpp"

using namespace closurelab::testing;
using closurelab::json;
namespace fs = std::filesystem;

TEST(H5PartTruncated, ATruncatedFileIsOneClearMessageAndNoLibraryNoise) {
  const fs::path work = fresh_work_folder("h5part_truncated");
  closurelab::ParticleSystem p;
  for (int k = 0; k < 200; ++k) p.add(0.01 * k, 0.005 * k, 1.0, 0, false);
  const fs::path file = work / "cut.h5part";
  closurelab::write_h5part(file.string(), {{0.0, p, true}});
  const auto full = fs::file_size(file);
  const json spec = {{"name", "s"},
                     {"kind", "snapshot_closure"},
                     {"base", {{"scene", {{"name", "poiseuille-uniform"}, {"n_y", 16}, {"n_x", 12}}},
                               {"snapshot", {{"file", file.string()}}}}}};
  write_text(work / "spec.json", spec.dump());
  for (const double keep : {0.1, 0.5, 0.99}) {
    fs::resize_file(file, static_cast<std::uintmax_t>(keep * static_cast<double>(full)));
    fs::remove_all(work / "out");
    const CliOutcome o = run_closurelab(work, "run " + (work / "spec.json").string() + " --out " + (work / "out").string());
    EXPECT_EQ(o.code, 2) << o.err;  // refused at validation (the file is read there), nothing run
    EXPECT_NE(o.err.find("is truncated"), std::string::npos) << o.err;
    EXPECT_NE(o.err.find("declares " + std::to_string(full)), std::string::npos) << o.err;
    EXPECT_EQ(o.err.find("infinite loop"), std::string::npos) << o.err;
    EXPECT_EQ(o.err.find("E,E"), std::string::npos) << o.err;
  }
}
