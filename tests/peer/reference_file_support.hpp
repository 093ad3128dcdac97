#pragma once
// Shared by the peer tests (tests/peer/): a particle snapshot written in PySPH's HDF5 layout or as CSV, a recursive
// comparison of two rows' numbers, a spec run (or refused) through the command line, and PySPH's particles read
// back from the committed text files of the peer scripts.
#include <filesystem>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "core/base/params.hpp"
#include "core/io/particle_snapshot.hpp"

namespace closurelab::testing {

// `s` as PySPH's HDFOutput writes a dump: /solver_data (attribute t), /particles/{fluid,solid}/arrays/{x,y,u,v,m}
// with the held-fixed particles in `solid` (the order changes: fluid first, then solid).
void write_pysph_layout(const std::string& file, const ParticleSnapshot& s);

// Every number of `a` within `tol` (absolute) of `b`, the same keys, sizes, strings and booleans; the largest
// difference into *worst.
void expect_close(const json& a, const json& b, double tol, const std::string& path, double* worst);

// Runs the spec {name, kind, base, axes} with `closurelab run` (its table in work/name, the reference store in
// work/store) and returns the table's rows (none, with a failed expectation, if the run failed).
json run_rows(const std::filesystem::path& work, const std::string& name, const std::string& kind, const json& base,
              const json& axes);

// The one row of `direct_base` (its direct SPH run) and the one row of `file_base` with reference.file = `file`,
// each checked: status ok, and the file row's record (expect_file_row) with `layout` and fixed_from "file".
std::pair<json, json> direct_and_file_rows(const std::filesystem::path& work, const json& direct_base, json file_base,
                                           const std::string& file, const std::string& layout);

// The direct run's final particles of `row`: the last step of its store entry's H5Part (under work/store) and the
// same particles written in PySPH's layout (work/direct_final.hdf5): {the H5Part, the PySPH file}.
std::pair<std::string, std::string> direct_particle_files(const std::filesystem::path& work, const json& row);

// `p` as closurelab's particle CSV (x,y,vx,vy,mass,phase[,fixed]) at full precision, every x mapped to
// x_scale x + x_shift and every y to y_scale y + y_shift (another box or particles outside it); returns the path.
std::string write_particles_csv(const std::filesystem::path& file, const ParticleSystem& p, bool fixed_column,
                                double x_scale = 1.0, double x_shift = 0.0, double y_scale = 1.0, double y_shift = 0.0);

// The one-cell reduced_model spec `base` is refused before anything runs: exit 2, the message naming the JSON
// path `path` (under /base) and saying `says`, and no table written.
void expect_refused(const std::filesystem::path& work, const std::string& name, const json& base,
                    const std::string& path, const std::string& says);

// The row of a cell whose reference is `file`: the file's record (path, size, checksum, layout), no direct run's
// record and no speed-up.
void expect_file_row(const json& row, const std::string& file, const std::string& layout);

// The rows `x y u v` of a committed peer file (tests/peer/data/*.txt; '#' lines skipped), in order; a failed
// expectation, and what was read so far, on a missing file or a short row.
std::vector<std::array<double, 4>> read_xyuv_rows(const std::string& file);

}  // namespace closurelab::testing
