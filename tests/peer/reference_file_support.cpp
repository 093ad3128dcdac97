#include "tests/peer/reference_file_support.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

#include "tests/support/cli_run.hpp"

namespace closurelab::testing {

namespace {

void write_array(hid_t group, const char* name, const std::vector<double>& v) {
  const hsize_t dims[1] = {v.size()};
  const hid_t space = H5Screate_simple(1, dims, nullptr);
  const hid_t set = H5Dcreate2(group, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Dclose(set);
  H5Sclose(space);
}

}  // namespace

void write_pysph_layout(const std::string& file, const ParticleSnapshot& s) {
  const hid_t f = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t solver = H5Gcreate2(f, "solver_data", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t scalar = H5Screate(H5S_SCALAR);
  const hid_t t = H5Acreate2(solver, "t", H5T_IEEE_F64LE, scalar, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(t, H5T_NATIVE_DOUBLE, &s.time);
  H5Aclose(t);
  H5Sclose(scalar);
  H5Gclose(solver);
  H5Gclose(H5Gcreate2(f, "particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  const ParticleSystem& p = s.particles;
  for (const int fixed : {0, 1}) {
    const std::string name = std::string("particles/") + (fixed ? "solid" : "fluid");
    H5Gclose(H5Gcreate2(f, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    const hid_t arrays = H5Gcreate2(f, (name + "/arrays").c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    std::vector<double> x, y, u, v, m;
    for (std::size_t a = 0; a < p.size(); ++a)
      if ((p.fixed[a] != 0) == (fixed != 0)) {
        x.push_back(p.x[a]), y.push_back(p.y[a]), u.push_back(p.vx[a]), v.push_back(p.vy[a]), m.push_back(p.mass[a]);
      }
    write_array(arrays, "x", x), write_array(arrays, "y", y), write_array(arrays, "u", u);
    write_array(arrays, "v", v), write_array(arrays, "m", m);
    H5Gclose(arrays);
  }
  H5Fclose(f);
}

void expect_close(const json& a, const json& b, double tol, const std::string& path, double* worst) {
  ASSERT_EQ(a.type(), b.type()) << path;
  if (a.is_object()) {
    ASSERT_EQ(a.size(), b.size()) << path;
    for (auto it = a.begin(); it != a.end(); ++it) {
      ASSERT_TRUE(b.contains(it.key())) << path << "/" << it.key();
      expect_close(it.value(), b.at(it.key()), tol, path + "/" + it.key(), worst);
    }
  } else if (a.is_array()) {
    ASSERT_EQ(a.size(), b.size()) << path;
    for (std::size_t k = 0; k < a.size(); ++k) expect_close(a[k], b[k], tol, path + "/" + std::to_string(k), worst);
  } else if (a.is_number()) {
    const double d = std::abs(a.get<double>() - b.get<double>());
    *worst = std::max(*worst, d);
    EXPECT_LE(d, tol) << path << ": " << a << " vs " << b;
  } else {
    EXPECT_EQ(a, b) << path;
  }
}

json run_rows(const std::filesystem::path& work, const std::string& name, const std::string& kind, const json& base,
              const json& axes) {
  const json spec = {{"name", name}, {"kind", kind}, {"base", base}, {"axes", axes}};
  write_text(work / (name + ".json"), spec.dump(1));
  const CliOutcome o = run_closurelab(work, "run " + (work / (name + ".json")).string() + " --out " +
                                                (work / name).string() + " --store " + (work / "store").string());
  EXPECT_EQ(o.code, 0) << o.err;
  if (o.code != 0) return json::array();
  return json::parse(read_text(work / name / (name + ".json"))).at("rows");
}

std::pair<json, json> direct_and_file_rows(const std::filesystem::path& work, const json& direct_base, json file_base,
                                           const std::string& file, const std::string& layout) {
  const json direct = run_rows(work, "direct", "reduced_model", direct_base, json::object());
  file_base["reference"] = {{"file", file}};
  const json from_file = run_rows(work, "file", "reduced_model", file_base, json::object());
  EXPECT_EQ(direct.size(), 1u);
  EXPECT_EQ(from_file.size(), 1u);
  if (direct.size() != 1 || from_file.size() != 1) return {json::object(), json::object()};
  EXPECT_EQ(direct[0].at("status"), "ok") << direct[0].dump();
  expect_file_row(from_file[0], file, layout);
  EXPECT_EQ(from_file[0]["reference_file"]["fixed_from"], "file");
  return {direct[0], from_file[0]};
}

std::pair<std::string, std::string> direct_particle_files(const std::filesystem::path& work, const json& row) {
  const std::string h5part =
      (work / "store" / row.at("direct_sph").at("reference_store").at("entry").get<std::string>() / "particles.h5part")
          .string();
  const std::string pysph = (work / "direct_final.hdf5").string();
  write_pysph_layout(pysph, read_particle_snapshot(h5part, -1));
  return {h5part, pysph};
}

std::string write_particles_csv(const std::filesystem::path& file, const ParticleSystem& p, bool fixed_column,
                                double x_scale, double x_shift, double y_scale, double y_shift) {
  std::string text = fixed_column ? "x,y,vx,vy,mass,phase,fixed\n" : "x,y,vx,vy,mass,phase\n";
  char line[256];
  for (std::size_t a = 0; a < p.size(); ++a) {
    std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g,%.17g,%d", p.x[a] * x_scale + x_shift,
                  p.y[a] * y_scale + y_shift, p.vx[a], p.vy[a], p.mass[a], p.phase[a]);
    text += line;
    text += fixed_column ? (p.fixed[a] ? ",1\n" : ",0\n") : "\n";
  }
  write_text(file, text);
  return file.string();
}

void expect_refused(const std::filesystem::path& work, const std::string& name, const json& base,
                    const std::string& path, const std::string& says) {
  const json spec = {{"name", name}, {"kind", "reduced_model"}, {"base", base}};
  write_text(work / (name + ".json"), spec.dump(1));
  const CliOutcome o = run_closurelab(work, "run " + (work / (name + ".json")).string() + " --out " +
                                                (work / name).string() + " --store " + (work / "store").string());
  EXPECT_EQ(o.code, 2) << name << ": " << o.err;
  EXPECT_NE(o.err.find("/base" + path), std::string::npos) << name << ": " << o.err;
  EXPECT_NE(o.err.find(says), std::string::npos) << name << ": " << o.err;
  EXPECT_FALSE(std::filesystem::exists(work / name / (name + ".json"))) << name << ": a table was written";
}

void expect_file_row(const json& row, const std::string& file, const std::string& layout) {
  ASSERT_EQ(row.at("status"), "ok") << row.dump();
  EXPECT_FALSE(row.contains("direct_sph"));
  const json& r = row.at("reference_file");
  EXPECT_EQ(r.at("path"), file);
  EXPECT_EQ(r.at("bytes").get<std::uintmax_t>(), std::filesystem::file_size(file));
  EXPECT_EQ(r.at("fnv1a64").get<std::string>().size(), 16u);
  EXPECT_EQ(r.at("layout"), layout);
  EXPECT_TRUE(row.at("cost").at("speed_up").is_null());  // no direct run timed: no speed-up, not 0
  EXPECT_TRUE(row.at("cost").contains("speed_up_note"));
  EXPECT_FALSE(row.at("cost").contains("direct_sph_wall_seconds"));
}

std::vector<std::array<double, 4>> read_xyuv_rows(const std::string& file) {
  std::vector<std::array<double, 4>> rows;
  std::ifstream in(file);
  EXPECT_TRUE(in) << file;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream row(line);
    std::array<double, 4> r{};
    if (!(row >> r[0] >> r[1] >> r[2] >> r[3])) {
      ADD_FAILURE() << file << ": " << line;
      return rows;
    }
    rows.push_back(r);
  }
  return rows;
}

}  // namespace closurelab::testing
