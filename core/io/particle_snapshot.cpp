#include "core/io/particle_snapshot.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "core/base/errors.hpp"
#include "core/io/h5part.hpp"
#include "core/io/pysph_output.hpp"

namespace closurelab {

void check_particles(const ParticleSystem& p, const std::string& what) {
  const std::size_t n = p.x.size();
  if (p.y.size() != n || p.vx.size() != n || p.vy.size() != n || p.mass.size() != n || p.phase.size() != n ||
      p.fixed.size() != n)
    throw ConfigError("", what + ": the particle arrays differ in length");
  for (std::size_t a = 0; a < n; ++a) {
    if (!std::isfinite(p.x[a]) || !std::isfinite(p.y[a]) || !std::isfinite(p.vx[a]) || !std::isfinite(p.vy[a]))
      throw ConfigError("", what + ": particle " + std::to_string(a) + " has a non-finite position or velocity");
    if (!(p.mass[a] > 0) || !std::isfinite(p.mass[a]))
      throw ConfigError("", what + ": particle " + std::to_string(a) + " has a mass that is not positive and finite");
    if (p.phase[a] < 0) throw ConfigError("", what + ": particle " + std::to_string(a) + " has a negative phase");
  }
}

namespace {

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::stringstream ss(line);
  while (std::getline(ss, cell, ',')) {
    const auto b = cell.find_first_not_of(" \t\r"), e = cell.find_last_not_of(" \t\r");
    out.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
  }
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

double parse_number(const std::string& s, const std::string& where) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(s, &used);
  } catch (...) {
    used = 0;
  }
  if (used == 0 || used != s.size()) throw ConfigError("", where + ": '" + s + "' is not a number");
  return v;
}

}  // namespace

ParticleSnapshot read_particle_csv(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw ConfigError("", "cannot open particle file '" + file + "'");
  std::string line;
  int line_no = 0;
  std::map<std::string, std::size_t> col;
  std::size_t width = 0;
  ParticleSnapshot s;
  ParticleSystem& p = s.particles;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t")] == '#') continue;
    const std::vector<std::string> cells = split_csv(line);
    const std::string where = file + ":" + std::to_string(line_no);
    if (col.empty()) {  // the header
      for (std::size_t c = 0; c < cells.size(); ++c)
        if (!col.emplace(cells[c], c).second)  // which of two 'vx' columns is the velocity? neither is assumed
          throw ConfigError("", where + ": the header names column '" + cells[c] + "' twice");
      for (const char* need : {"x", "y", "vx", "vy", "mass", "phase"})
        if (!col.count(need))
          throw ConfigError("", where + ": the header has no column '" + need + "' (needed: x,y,vx,vy,mass,phase)");
      s.has_fixed = col.count("fixed") > 0;
      width = cells.size();
      continue;
    }
    if (cells.size() != width)
      throw ConfigError("", where + ": " + std::to_string(cells.size()) + " fields, the header has " +
                                std::to_string(width));
    const auto num = [&](const char* name) { return parse_number(cells[col.at(name)], where); };
    const double phase = num("phase");
    if (phase != std::floor(phase) || phase < 0 || phase > 1e6)
      throw ConfigError("", where + ": phase '" + cells[col.at("phase")] + "' is not a non-negative integer");
    p.add(num("x"), num("y"), num("mass"), static_cast<int>(phase), s.has_fixed && num("fixed") != 0);
    p.vx.back() = num("vx");
    p.vy.back() = num("vy");
  }
  if (col.empty()) throw ConfigError("", "'" + file + "' is empty (no header x,y,vx,vy,mass,phase)");
  check_particles(p, file);
  return s;
}

ParticleSnapshot read_particle_snapshot(const std::string& file, int step) {
  const auto dot = file.rfind('.');
  const std::string ext = dot == std::string::npos ? "" : file.substr(dot + 1);
  if (ext == "csv") {
    if (step != 0 && step != -1) throw ConfigError("", "'" + file + "' is a CSV file: one step (0 or -1)");
    return read_particle_csv(file);
  }
  if (ext == "h5part" || ext == "h5" || ext == "hdf5") {
    if (!is_pysph_output(file)) return read_h5part(file, step);
    if (step != 0 && step != -1) throw ConfigError("", "'" + file + "' is a PySPH output file: one step (0 or -1)");
    return read_pysph_output(file);  // core/io/pysph_output.hpp: PySPH's own layout
  }
  if (ext == "npz") throw ConfigError("", pysph_npz_refusal(file));
  throw ConfigError("", "'" + file + "': unknown particle file type '." + ext +
                            "'; known: .h5part, .h5, .hdf5 (H5Part or PySPH output), .csv");
}

}  // namespace closurelab
