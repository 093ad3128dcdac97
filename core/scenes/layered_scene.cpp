// Scene "layered-two-phase" (§7, DESIGN.md §5): a channel of width L between walls of 3η' (whole lattice rows)
// outside it, so the box is L + 2·3η' high; n_y fluid rows (ε' = L/n_y); layers of the less viscous fluid
// (μ = 100, phase 1) in the more viscous one (μ = 200, phase 0); equal densities; uniform force g along x;
// van der Waals EOS (7.1) with k* across phases (core/sph/equation_of_state.hpp). The analytic steady solution is
// piecewise parabolic (LayeredChannelFlow, core/scenes/analytic.hpp) with the interfaces between lattice rows.
#include "core/scenes/layered_scene.hpp"

#include <cmath>
#include <map>
#include <memory>

#include "core/scenes/analytic.hpp"
#include "core/base/errors.hpp"
#include "core/base/memory_limit.hpp"
#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_kernel.hpp"

namespace closurelab {

namespace {

constexpr int kReferenceRows = 192;  // the paper's lattice: ε' = L/192 (§7)

const std::map<std::string, LayerLayout>& paper_layouts() {
  // DESIGN.md §5, start rows of the less-viscous layers in the 192-row lattice (the paper's Fig. 5).
  static const std::map<std::string, LayerLayout> m = {
      {"case1", {{30, 45, 90, 140, 152}, 9}},  // width 3η'/4; two gaps narrower than a layer
      {"case2", {{25, 70, 115, 160}, 9}},      // width 3η'/4
      {"case3", {{30, 120}, 27}},              // width 9η'/4
  };
  return m;
}

ParamSchema layered_schema() {
  ParamSchema schema{
      string_param("case", "case1",
                   "layer layout (DESIGN.md par. 5): case1/case2/case3 in rows of the 192-row lattice, scaled by n_y/192; "
                   "custom: layer_rows and layer_width",
                   {"case1", "case2", "case3", "custom"}),
      array_param("layer_rows", json::array(), "custom only: start rows of the less-viscous layers (row 0 at the lower "
                                                "wall, rows of this scene's n_y lattice)"),
      integer_param("layer_width", 0, "custom only: layer width in rows", 0, {}),
      integer_param("n_y", kReferenceRows, "fluid rows across the channel (epsilon' = L / n_y)", 8, 4096),
      integer_param("n_x", 12, "particle columns of the periodic strip (x-extent = n_x epsilon')", 4, 100000),
      number_param("eta_over_l", 1.0 / 16.0, "averaging scale eta'/L; walls are 3 eta' thick, outside the channel", 0.0,
                   {}, true),
      number_param("l", 1.0, "channel width L between the walls", 0.0, {}, true),
      number_param("rho", 1.0, "density of both fluids", 0.0, {}, true),
      number_param("mu_viscous", 200.0, "viscosity of the more viscous fluid (phase 0, also the walls' phase)", 0.0, {},
                   true),
      number_param("mu_less_viscous", 100.0, "viscosity of the less viscous fluid (phase 1, the layers)", 0.0, {}, true),
      number_param("g", 1.0, "body force per unit mass along x", {}, {}),
      string_param("pair_viscosity_mean", "arithmetic",
                   "mu_ij of unlike particles in (5.1): arithmetic mu_i + mu_j or harmonic 4 mu_i mu_j / (mu_i + mu_j)",
                   {"arithmetic", "harmonic"}),
      number_param("vdw_phi", 0.5, "van der Waals (7.1): c_1 n0, in (0, 1)", 0.0, 1.0, true),
      number_param("vdw_a", 1.0, "van der Waals (7.1): c_2 n0 / (k_B T), in [0, min(1/(1-phi), 1/(2(1-phi)^2)))", 0.0, {}),
      number_param("k_star", 0.5, "van der Waals (7.1): k_ij across phases, in [0, 1) (smaller: stronger surface tension)",
                   0.0, {}),
  };
  for (const ParamSchema& more : {wall_model_params(), sph_discretization_params()})
    schema.insert(schema.end(), more.begin(), more.end());
  return schema;
}

}  // namespace

LayerLayout layered_layout(const json& p) {
  const std::string name = p.at("case").get<std::string>();
  const int ny = p.at("n_y").get<int>();
  const json& rows = p.at("layer_rows");
  LayerLayout lay;
  std::string where;  // the JSON path blamed for a bad layout
  if (name == "custom") {
    if (rows.empty()) throw ConfigError("/layer_rows", "case custom needs the start rows of the layers");
    for (std::size_t k = 0; k < rows.size(); ++k) {
      if (!rows[k].is_number_integer() || rows[k].get<double>() < 0 || rows[k].get<double>() >= ny)
        throw ConfigError("/layer_rows/" + std::to_string(k),
                          "expected an integer row in [0, n_y) = [0, " + std::to_string(ny) + "), got " + rows[k].dump());
      lay.start_rows.push_back(rows[k].get<int>());
    }
    lay.width = p.at("layer_width").get<int>();
    if (lay.width < 1) throw ConfigError("/layer_width", "case custom needs layer_width >= 1 row");
    where = "/layer_rows";
  } else {
    if (!rows.empty() || p.at("layer_width").get<int>() != 0)
      throw ConfigError("/layer_rows", "layer_rows and layer_width are for case custom only (case is '" + name + "')");
    const LayerLayout& ref = paper_layouts().at(name);  // the schema admits only known names
    const double scale = static_cast<double>(ny) / kReferenceRows;
    for (int r : ref.start_rows) lay.start_rows.push_back(static_cast<int>(std::lround(r * scale)));
    lay.width = static_cast<int>(std::lround(ref.width * scale));
    if (lay.width < 1)
      throw ConfigError("/n_y", "case " + name + ": the layers (" + std::to_string(ref.width) + " of 192 rows) vanish at n_y = " +
                                    std::to_string(ny) + "; raise n_y");
    where = "/n_y";
  }
  for (std::size_t k = 0; k < lay.start_rows.size(); ++k) {
    const int s = lay.start_rows[k];
    const std::string at = name == "custom" ? where + "/" + std::to_string(k) : where;
    if (s < 1 || s + lay.width > ny - 1)
      throw ConfigError(at, "layer " + std::to_string(k) + " (rows " + std::to_string(s) + ".." + std::to_string(s + lay.width - 1) +
                                ") is outside the channel's rows 1.." + std::to_string(ny - 2) +
                                " (at least one row of the more viscous fluid must separate a layer from a wall)");
    if (k > 0 && s <= lay.start_rows[k - 1] + lay.width)
      throw ConfigError(at, "layer " + std::to_string(k) + " (from row " + std::to_string(s) + ") overlaps or touches layer " +
                                std::to_string(k - 1) + " (rows " + std::to_string(lay.start_rows[k - 1]) + ".." +
                                std::to_string(lay.start_rows[k - 1] + lay.width - 1) + "); layers must ascend with a gap");
  }
  return lay;
}

void register_layered_scene(Registry& r) {
  r.scenes.add(
      {"layered-two-phase",
       "two-phase layered channel flow (par. 7): less-viscous layers in a more viscous fluid, van der Waals EOS (7.1), "
       "walls of 3 eta' outside the channel of width L",
       layered_schema()},
      [](const json& p) {
        auto s = std::make_unique<Scene>();
        s->name = "layered-two-phase";
        s->params = p;
        const LayerLayout lay = layered_layout(p);
        const double l = p.at("l").get<double>(), eta_over_l = p.at("eta_over_l").get<double>();
        s->ny = p.at("n_y").get<int>();
        s->nx = p.at("n_x").get<int>();
        check_particle_memory(s->nx, 2L * s->ny, "/n_x");  // fluid rows plus the walls' (at most as many)
        s->dx = l / s->ny;
        s->eta = eta_over_l * l;
        if (eta_over_l > 1.0 / 6.0)
          throw ConfigError("/eta_over_l", "eta' too large: the averaging window (6 eta') must fit in the channel, "
                                           "eta_over_l <= 1/6");
        // Walls of 3η' in whole rows (3η'/ε' rounded), outside the channel.
        const int wall_rows = static_cast<int>(std::lround(3.0 * s->eta / s->dx));
        read_sph_discretization(*s, p, "");
        const double support = s->smoothing_kernel().support();
        if (wall_rows * s->dx < support)
          throw ConfigError("/eta_over_l", "walls (3 eta' = " + std::to_string(wall_rows) +
                                               " rows) thinner than the SPH support; raise eta' or n_y");
        s->ny = s->ny + 2 * wall_rows;  // lattice rows of the box, walls included
        s->box = PeriodicBox{s->nx * s->dx, s->ny * s->dx, true, false};
        check_strip_width(*s, "");
        s->has_walls = true;
        s->wall_lo = wall_rows * s->dx;
        s->wall_hi = s->wall_lo + l;
        s->wall_model = parse_name<WallModel>(p.at("wall_model").get<std::string>(), "/wall_model");
        s->ghost_beta_max = p.at("ghost_beta_max").get<double>();
        s->rho0 = p.at("rho").get<double>();
        const double mu0 = p.at("mu_viscous").get<double>(), mu1 = p.at("mu_less_viscous").get<double>();
        s->phase_viscosity = {mu0, mu1};
        s->pair_viscosity_mean = parse_name<PairViscosityMean>(p.at("pair_viscosity_mean").get<std::string>(), "/pair_viscosity_mean");

        // Phases by fluid row; the walls take phase 0 (the layers never touch them).
        const int fluid_rows = p.at("n_y").get<int>();
        std::vector<int> row_phase(fluid_rows, 0);
        for (int st : lay.start_rows)
          for (int k = 0; k < lay.width; ++k) row_phase[st + k] = 1;
        const double lo = s->wall_lo, dx = s->dx;
        s->phase_at = [row_phase, lo, dx](double y) {
          const double r = std::floor((y - lo) / dx);
          if (r < 0.0 || r >= static_cast<double>(row_phase.size())) return 0;
          return row_phase[static_cast<std::size_t>(r)];
        };
        std::vector<double> segment_mu{mu0};
        for (int st : lay.start_rows) {
          s->interfaces.push_back(lo + st * dx);
          segment_mu.push_back(mu1);
          s->interfaces.push_back(lo + (st + lay.width) * dx);
          segment_mu.push_back(mu0);
        }
        const double g = p.at("g").get<double>();
        s->force_x = [g](double) { return g; };
        const auto flow = std::make_shared<LayeredChannelFlow>(s->wall_lo, s->wall_hi, s->interfaces, segment_mu, s->rho0, g);
        s->analytic_vx = [flow](double y) { return flow->velocity(y); };
        s->analytic_peak = flow->peak();
        s->sound_speed = p.at("sound_speed_factor").get<double>() * std::max(s->analytic_peak, 1e-300);
        // (7.1) at the lattice number density n0, m = ρ0/n0, with c = sound_speed at n0.
        const double m = s->particle_mass();
        s->van_der_waals = VanDerWaalsEos::from_liquid(s->rho0 / m, m, s->sound_speed, p.at("vdw_phi").get<double>(),
                                                       p.at("vdw_a").get<double>(), p.at("k_star").get<double>(), "");
        s->background_pressure = 0.0;  // not used under (7.1)
        s->x_invariant = true;
        return s;
      });
}

}  // namespace closurelab
