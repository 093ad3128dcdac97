#include "core/closure/parameter_choice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/base/errors.hpp"

namespace closurelab {

namespace {
// Six significant digits at any scale (std::to_string prints 1e-9 as 0.000000).
std::string short_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// The note of a choice at the edge of the scanned family (most regularized first): the rule's optimum may lie
// beyond it.
std::string scan_edge_note(ParameterRule rule, const std::string& name, double chosen, double first, double last,
                           bool at_first) {
  return to_string(rule) + " chose " + name + " = " + short_number(chosen) + " at the edge of its scan [" +
         short_number(std::min(first, last)) + ", " + short_number(std::max(first, last)) + "] (the " +
         (at_first ? "most" : "least") + " regularized member scanned): the rule's optimum may lie outside the " +
         "scan; widen the scan";
}
}  // namespace


std::vector<double> log_grid_descending(double hi, double lo, int count) {
  std::vector<double> g;
  if (count <= 1) return {hi};
  const double a = std::log(hi), c = std::log(lo);
  for (int i = 0; i < count; ++i) g.push_back(std::exp(a + (c - a) * i / (count - 1)));
  return g;
}

int lcurve_corner(const std::vector<RecordedPoint>& p) {
  if (p.size() < 3) return p.empty() ? -1 : static_cast<int>(p.size()) - 1;
  // The L-curve (log ‖r‖, log ‖x‖), scaled to the unit square. Three-point curvature is fragile on densely
  // sampled or jittery curves (iterative methods), so the corner is sought on the curve's convex hull facing
  // the origin (the lower hull, as in the pruning idea of Hansen, Jensen & Rodriguez 2007): the hull vertex where
  // the hull turns most sharply.
  // Members with ‖x‖ = 0 or ‖r‖ = 0 (the x = 0 start of an iteration, an exact fit) are not on the log–log
  // curve; they are left out.
  std::vector<int> on_curve;
  for (size_t i = 0; i < p.size(); ++i)
    if (p[i].residual_norm > 0 && p[i].solution_norm > 0 && std::isfinite(p[i].residual_norm) &&
        std::isfinite(p[i].solution_norm))
      on_curve.push_back(static_cast<int>(i));
  if (on_curve.size() < 3) return on_curve.empty() ? static_cast<int>(p.size()) - 1 : on_curve.back();
  std::vector<Eigen::Vector2d> q(on_curve.size());
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (size_t i = 0; i < on_curve.size(); ++i) {
    const RecordedPoint& r = p[static_cast<size_t>(on_curve[i])];
    q[i] = {std::log(r.residual_norm), std::log(r.solution_norm)};
    lo = lo.cwiseMin(q[i]);
    hi = hi.cwiseMax(q[i]);
  }
  const Eigen::Vector2d span = (hi - lo).cwiseMax(Eigen::Vector2d(1e-12, 1e-12));
  for (auto& v : q) v = (v - lo).cwiseQuotient(span);
  std::vector<int> idx(q.size());
  for (size_t i = 0; i < q.size(); ++i) idx[i] = static_cast<int>(i);
  std::sort(idx.begin(), idx.end(), [&](int a, int b) {
    return q[a].x() < q[b].x() || (q[a].x() == q[b].x() && q[a].y() < q[b].y());
  });
  auto cross = [&](int o, int a, int b) {
    return (q[a] - q[o]).x() * (q[b] - q[o]).y() - (q[a] - q[o]).y() * (q[b] - q[o]).x();
  };
  std::vector<int> hull;  // lower hull by Andrew's monotone chain, left to right
  for (int k : idx) {
    while (hull.size() >= 2 && cross(hull[hull.size() - 2], hull.back(), k) <= 0) hull.pop_back();
    hull.push_back(k);
  }
  int best = hull.size() > 2 ? hull[1] : static_cast<int>(q.size()) / 2;
  double best_turn = -1.0;
  for (size_t h = 1; h + 1 < hull.size(); ++h) {
    const Eigen::Vector2d in = (q[hull[h]] - q[hull[h - 1]]).normalized(), out = (q[hull[h + 1]] - q[hull[h]]).normalized();
    const double turn = std::acos(std::clamp(in.dot(out), -1.0, 1.0));
    if (turn > best_turn) {
      best_turn = turn;
      best = hull[h];
    }
  }
  return on_curve[static_cast<size_t>(best)];
}

namespace {
void take(DeconvolutionResult& r, const ScanPoint& p) {
  r.x = p.solution();
  r.stats.residual_norm = p.residual_norm;
  r.stats.solution_norm = p.solution_norm;
  r.stats.chosen_parameter = p.parameter;
  r.cost.matvecs = std::max(r.cost.matvecs, p.matvecs);
  if (!p.issue.empty()) {
    r.status = DeconvolutionStatus::numerical_issue;
    r.stats.message = p.issue;
  }
}
}  // namespace

DeconvolutionResult choose_by_rule(const Deconvolver& d, const Eigen::VectorXd& b, ParameterRule rule,
                                   double noise_level, double safety, const Seminorm& lcurve_seminorm,
                                   const std::string& parameter_name) {
  DeconvolutionResult r;
  r.stats.rule = to_string(rule);
  int visited = 0;
  bool taken = false;
  if (rule == ParameterRule::discrepancy) {
    // The first member with ‖r‖ <= τδ. If none qualifies, the member of smallest residual (the last one for
    // methods whose residual decreases monotonically; CG's residual does not).
    const double target = safety * noise_level;
    int best_index = -1;
    double best_residual = std::numeric_limits<double>::infinity();
    long total_matvecs = 0;
    bool met_at_first = false;  // the first member scanned meets it: a more regularized one may too
    d.scan(b, [&](const ScanPoint& p) {
      const bool met = p.residual_norm <= target;
      total_matvecs = p.matvecs;
      if (visited == 0) met_at_first = met && p.issue.empty() && p.solution_norm > 0;  // x = 0: nothing is more
      if (p.residual_norm < best_residual) {
        best_residual = p.residual_norm;
        best_index = visited;
      }
      ++visited;
      if (met || !p.issue.empty() || (p.last && best_index == visited - 1)) {
        take(r, p);
        taken = true;
        if (!met && p.issue.empty()) best_index = -1;  // taken as the smallest-residual member
        return false;
      }
      return !p.last;
    });
    if (!taken) {
      if (best_index < 0) throw NumericalError(d.name() + ": the parameter scan visited no solution");
      int index = 0;
      d.scan(b, [&](const ScanPoint& p) {
        if (index++ < best_index) return true;
        take(r, p);
        taken = true;
        return false;
      });
      r.cost.matvecs += total_matvecs;
      best_index = -1;
    }
    if (r.status == DeconvolutionStatus::converged && !(r.stats.residual_norm <= target)) {
      r.status = DeconvolutionStatus::no_convergence;
      r.stats.message = "discrepancy principle not met: smallest residual " + short_number(r.stats.residual_norm) +
                        " > tau*delta = " + short_number(target) + "; returned the smallest-residual member";
    }
    if (met_at_first && r.status == DeconvolutionStatus::converged)
      r.stats.note = "discrepancy chose " + parameter_name + " = " + short_number(r.stats.chosen_parameter) +
                     ", the first (most regularized) member of its scan, which meets the principle already: a more " +
                     "regularized member outside the scan may meet it too; widen the scan";
    r.stats.iterations = visited;
    return r;
  }
  std::vector<RecordedPoint> pts;
  long total_matvecs = 0;
  std::string issue;
  d.scan(b, [&](const ScanPoint& p) {
    const bool seminorm = rule == ParameterRule::lcurve && lcurve_seminorm;
    pts.push_back(RecordedPoint{p.parameter, p.residual_norm, seminorm ? lcurve_seminorm(p.solution()) : p.solution_norm,
                                p.gcv});
    total_matvecs = p.matvecs;
    if (!p.issue.empty()) issue = p.issue;
    return p.issue.empty();
  });
  if (pts.empty()) throw NumericalError(d.name() + ": the parameter scan visited no solution");
  int pick = -1;
  if (rule == ParameterRule::gcv) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < pts.size(); ++i)
      if (pts[i].gcv >= 0 && std::isfinite(pts[i].gcv) && pts[i].gcv < best) {
        best = pts[i].gcv;
        pick = static_cast<int>(i);
      }
    if (pick < 0) throw ConfigError("/rule", d.name() + " cannot evaluate the GCV function");
  } else {
    pick = lcurve_corner(pts);
  }
  int index = 0;
  d.scan(b, [&](const ScanPoint& p) {
    if (index++ < pick) return true;
    take(r, p);
    taken = true;
    return false;
  });
  if (!taken) throw NumericalError(d.name() + ": the second scan did not reach the chosen member");
  r.cost.matvecs += total_matvecs;
  if (!issue.empty()) {
    r.status = DeconvolutionStatus::numerical_issue;
    r.stats.message = issue;
  } else if (pick == 0 || pick + 1 == static_cast<int>(pts.size())) {
    r.stats.note = scan_edge_note(rule, parameter_name, pts[static_cast<size_t>(pick)].parameter, pts.front().parameter,
                                  pts.back().parameter, pick == 0);
  }
  r.stats.iterations = static_cast<int>(pts.size());
  return r;
}

}  // namespace closurelab
