#include "experiments/kinds/reduced_sections.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/base/errors.hpp"
#include "core/closure/forward_operator.hpp"
#include "core/sph/engine_version.hpp"
#include "core/sph/sph_run.hpp"
#include "experiments/kinds/cell_config.hpp"
#include "experiments/kinds/provenance.hpp"

namespace closurelab {

void check_operator_shape(const json& closure, long rows, long cols, const std::string& path) {
  if (rows == cols) return;
  const json& d = closure.at("deconvolver");
  const std::string name = d.value("name", "");
  std::string needs;
  if (name == "landweber" && d.value("lift", "none") == "none")
    needs = "landweber with lift = none (the series (4.3)/(4.9)) needs a square operator; use coarse_coarse or "
            "fine_fine, lift = interpolation, landweber_relaxed or cgls";
  else if (name == "tikhonov" && d.value("form", "") == "paper")
    needs = "tikhonov's paper form (A + alpha C) x = b needs a square operator; use coarse_coarse or fine_fine, or "
            "form least_squares";
  if (needs.empty()) return;
  throw ConfigError(path + "/closure/discretization",
                    "the " + closure.at("discretization").get<std::string>() + " operator is " + std::to_string(rows) +
                        " x " + std::to_string(cols) + " (data x unknowns), not square: " + needs);
}

void check_prior_on_2d_operator(const json& d, const std::string& path) {
  if (d.value("regularizer", "") == "first_difference_zero_ends")
    throw ConfigError(path + "/closure/deconvolver/regularizer",
                      "first_difference_zero_ends ends its links at a column's walls and needs a 1D solution mesh; "
                      "the 2D model's operator is 2D: use first_difference or identity");
}

void check_truncation_rank(const json& resolved_deconvolver, long rows, long cols, const std::string& shape,
                           bool under_rule, const std::string& path) {
  const json& d = resolved_deconvolver;
  if (d.value("name", "") != "tsvd" || d.value("truncation", "index") != "index" || !d.contains("k")) return;
  const long k = d.at("k").get<long>(), most = std::min(rows, cols);
  if (k <= most) return;
  throw ConfigError(path + "/closure/deconvolver/k",
                    "tsvd keeps k = " + std::to_string(k) + " singular values, above the rank of the closure's operator: it is " +
                        std::to_string(rows) + " x " + std::to_string(cols) + " at most (" + shape +
                        "), so it has at most " + std::to_string(most) + " singular values; use k <= " +
                        std::to_string(most) +
                        (under_rule ? " (pass 1 of the two-pass rule runs at the configured k)" : ""));
}

ParamSchema reference_schema() {
  return {bool_param("direct_sph", true, "run the direct SPH of the same scene as a reference (and for the speed-up)"),
          object_param("solver", json::object(), "direct SPH solver parameters (as in direct_sph_validation)"),
          number_param("observe_spacing_over_eta", 0.25, "mesh spacing / eta' for the direct run's steady test", 0.01, 10.0)};
}

void check_snapshot_times(const json& times, const std::string& path) {
  double previous = 0.0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const json& t = times[k];
    if (!t.is_number() || !std::isfinite(t.get<double>()) || t.get<double>() <= previous)
      throw ConfigError(path + "/" + std::to_string(k), "snapshot times must be finite numbers, positive and ascending");
    previous = t.get<double>();
  }
}

ParamSchema transient_schema() {
  return {array_param("t_over_tau", json::array(),
                      "snapshot times t / tau (ascending), tau the scene's time scale: the cellular mode's decay time "
                      "1 / (2 k^2 nu), else the advective time L / v_max (L the channel width, the cavity's side, or L_y "
                      "without walls; v_max the analytic peak); t_star, the column model's earlier name of the same times, is read "
                      "as t_over_tau; the final state is always reported as well")};
}

std::string transient_times_key(const json& cell) {
  const bool legacy = cell.is_object() && cell.contains("transient") && cell["transient"].is_object() &&
                      cell["transient"].contains("t_star");
  return legacy ? "t_star" : "t_over_tau";
}

json resolve_transient(const json& cell, const std::string& path) {
  const std::string key = transient_times_key(cell);
  json section = cell.is_object() && cell.contains("transient") ? cell["transient"] : json();
  if (key == "t_star") {
    if (section.contains("t_over_tau"))
      throw ConfigError(path + "/transient/t_star", "t_star is the earlier name of t_over_tau; give one of them");
    section["t_over_tau"] = section["t_star"];
    section.erase("t_star");
  }
  json out = resolve_section(json{{"transient", section}}, "transient", transient_schema(), path);
  check_snapshot_times(out["t_over_tau"], path + "/transient/" + key);
  return out;
}

std::vector<double> transient_times(const json& transient, const Scene& scene) {
  std::vector<double> times;
  for (const json& t : transient.at("t_over_tau")) times.push_back(t.get<double>() * scene.time_scale());
  return times;
}

json upgraded_reduced_params(json params) {
  if (!params.is_object()) return params;
  if (params.contains("transient") && params["transient"].is_object() && params["transient"].contains("t_star")) {
    json& t = params["transient"];
    t["t_over_tau"] = t["t_star"];
    t.erase("t_star");
  }
  if (params.contains("timing") && params["timing"].is_object() && !params["timing"].contains("min_seconds"))
    params["timing"]["min_seconds"] = 0.0;
  if (params.contains("reference") && params["reference"].is_object() && params["reference"].contains("solver"))
    params["reference"]["solver"] = upgraded_sph_solver_params(params["reference"]["solver"]);
  // arkode_imex rows stored before its linear_solver existed ran GMRES.
  if (params.contains("solver") && params["solver"].is_object() && params["solver"].contains("time_integration")) {
    json& ti = params["solver"]["time_integration"];
    if (ti.is_object() && ti.value("name", "") == "arkode_imex" && !ti.contains("linear_solver"))
      ti["linear_solver"] = "gmres";
  }
  return params;
}

ParamSchema reduced_timing_schema() { return timing_schema(); }

RepeatedReducedRuns repeat_reduced_run(const std::function<ReducedRunSeconds()>& run_once, const TimingPolicy& policy) {
  RepeatedReducedRuns out;
  out.setup_min = out.loop_min = std::numeric_limits<double>::infinity();
  std::vector<double> cpu;
  out.total = repeat_until_stable(
      [&] {
        const double cpu0 = process_cpu_seconds();
        const ReducedRunSeconds s = run_once();
        cpu.push_back(process_cpu_seconds() - cpu0);
        out.setup_min = std::min(out.setup_min, s.setup);
        out.loop_min = std::min(out.loop_min, s.loop);
        return s.setup + s.loop;
      },
      policy);
  out.cpu = timing_stats(std::move(cpu));
  return out;
}

void add_reduced_timing(json& cost, const RepeatedReducedRuns& runs, const json* direct_run) {
  cost["setup_seconds"] = runs.setup_min;
  cost["wall_seconds"] = runs.loop_min;
  cost["reduced_timing"] = runs.total.to_json();
  cost["reduced_timing"]["cpu"] = {{"min_seconds", runs.cpu.min}, {"median_seconds", runs.cpu.median},
                                   {"max_seconds", runs.cpu.max}, {"spread", runs.cpu.spread()},
                                   {"range", runs.cpu.range()}};
  if (!direct_run) return;
  const double direct_cpu = direct_run->value("cpu_seconds", 0.0);
  if (direct_cpu > 0 && runs.cpu.min > 0) {
    cost["direct_sph_cpu_seconds"] = direct_cpu;
    cost["speed_up_cpu"] = direct_cpu / runs.cpu.min;
    cost["speed_up_cpu_at_median"] = runs.cpu.median > 0 ? direct_cpu / runs.cpu.median : 0.0;
  } else {
    cost["speed_up_cpu"] = nullptr;
    cost["speed_up_cpu_note"] = "none: the direct run's record has no CPU time (a store entry from before it was recorded)";
  }
  const double direct_seconds = direct_run->at("wall_seconds").get<double>();
  cost["direct_sph_wall_seconds"] = direct_seconds;
  // Against the reduced model's whole cost, setup included (the direct run's setup is in its wall time).
  cost["speed_up"] = runs.total.min > 0 ? direct_seconds / runs.total.min : 0.0;
  cost["speed_up_at_median"] = runs.total.median > 0 ? direct_seconds / runs.total.median : 0.0;
  // The direct run is timed once (seconds to minutes); where it was computed by another commit or on another
  // host (a reused store entry), the row says so.
  const json by = direct_run->contains("reference_store")
                      ? direct_run->at("reference_store").value("computed_by", json::object())
                      : json::object();
  const json here = provenance("");
  json timing = {{"repeats", 1},
                 {"git_commit", by.value("git_commit", "unknown")},
                 {"dirty", by.value("dirty", false)},
                 {"host", by.value("host", "unknown")},
                 {"date_utc", by.value("date_utc", "unknown")},
                 {"threads", by.value("threads", 0)},
                 {"same_commit", by.value("git_commit", "") == here.at("git_commit").get<std::string>() &&
                                     by.value("dirty", false) == here.at("dirty").get<bool>()},
                 {"same_host", by.value("host", "") == here.at("host").get<std::string>()}};
  // A store entry is reused only by the engine version that computed it (its key holds the version).
  timing["engine_version"] = sph_engine_version;
  cost["direct_sph_timing"] = timing;
}

void finish_reduced_row(json& row, json errors, json cost, const RepeatedReducedRuns& timing, bool repeats_identical,
                        const DeconvolutionIssues& deconvolution_issues, const json* direct_run) {
  add_reduced_timing(cost, timing, direct_run);
  cost["repeats_identical"] = repeats_identical;
  cost["peak_memory_mib"] = peak_memory_mib();
  row["errors"] = std::move(errors);
  row["cost"] = std::move(cost);
  propagate_worst_status(row, deconvolution_issues, direct_run);
  // A run that failed (diverged, gave up) did not compute what the direct run computed: its time is no speed-up.
  if (row.value("status", "ok") != "ok" && row["cost"].contains("speed_up")) {
    for (const char* key : {"speed_up", "speed_up_at_median", "speed_up_cpu", "speed_up_cpu_at_median"})
      if (row["cost"].contains(key)) row["cost"][key] = nullptr;
    row["cost"]["speed_up_note"] = "none: the reduced run's status is " + row["status"].get<std::string>();
  }
  add_rule_notes(row);
}

void add_rule_notes(json& row) {
  if (!row.contains("reduced_model") || !row.at("reduced_model").is_object()) return;
  const json& run = row.at("reduced_model");
  std::string note;
  auto append = [&note](const std::string& s) { note += (note.empty() ? "" : "; ") + s; };
  if (run.contains("parameter_choice") && run.at("parameter_choice").contains("notes")) {
    const json& n = run.at("parameter_choice").at("notes");
    append("the closure's parameter rule chose at the edge of its scan in " +
           std::to_string(n.at("solves").get<long>()) + " solve(s); the first: " + n.at("first").get<std::string>());
  }
  if (run.contains("two_pass_rule")) {
    const json& t = run.at("two_pass_rule");
    if (t.contains("rule_note")) append("the two-pass rule: " + t.at("rule_note").get<std::string>());
    for (const char* what : {"velocity", "density"})
      if (t.contains(what) && t.at(what).contains("rule_note"))
        append(std::string("the two-pass rule (") + what + "): " + t.at(what).at("rule_note").get<std::string>());
  }
  if (!note.empty()) row["note"] = note;
}

void propagate_worst_status(json& row, const DeconvolutionIssues& deconvolution_issues, const json* direct_run) {
  if (row.value("status", "") != "ok") return;
  if (deconvolution_issues.solves > 0) {
    row["status"] = "numerical_issue";
    row["message"] = "the closure's deconvolution reported a numerical issue in " +
                     std::to_string(deconvolution_issues.solves) + " solve(s); the first: " + deconvolution_issues.first;
    return;
  }
  if (direct_run && direct_run->contains("status")) {
    const std::string s = direct_run->at("status").get<std::string>();
    if (s != "converged" && s != "target_time") {
      row["status"] = s == "numerical_issue" ? "numerical_issue" : "no_convergence";
      row["message"] = "the direct SPH reference ended " + s +
                       (direct_run->contains("message") ? " (" + direct_run->at("message").get<std::string>() + ")" : "") +
                       ": the errors against it measure a flow it did not reach";
    }
  }
}

}  // namespace closurelab
