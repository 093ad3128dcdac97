// `closurelab deconvolve --matrix A.mtx --rhs b.mtx ...` (its options: the table deconvolve_command_spec).
// Deconvolution of a user system read from Matrix Market files with any registered deconvolver (the same
// strategies the experiments use; no second code path). Prints one JSON object: the resolved method, the
// operator's size and storage, status, statistics, cost, the relative error when the truth is given, and the
// solution file (or the solution inline when --out is not given). Errors: message on stderr, exit code 2
// (bad input) or 1 (numerical failure).
#include "experiments/runner/deconvolve_command.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>

#include "core/closure/deconvolver.hpp"
#include "core/base/errors.hpp"
#include "core/base/metrics.hpp"
#include "core/closure/forward_operator.hpp"
#include "core/io/matrix_market.hpp"
#include "core/base/registry.hpp"
#include "experiments/runner/command_options.hpp"

namespace closurelab {

namespace {

struct Options {
  std::string matrix, rhs, x_true, method, out;
  json params = json::object();
  double noise_level = 0.0;
};

Options parse(int argc, char** argv, const Registry& registry) {
  const ParsedArgs args = parse_command_line(deconvolve_command_spec(registry), argc, argv);
  Options o;
  o.matrix = args.value("--matrix");
  o.rhs = args.value("--rhs");
  o.x_true = args.value("--x-true");
  o.method = args.value("--method");
  o.out = args.value("--out");
  if (args.has("--noise-level")) o.noise_level = std::strtod(args.value("--noise-level").c_str(), nullptr);
  for (const std::string& kv : args.all("--param")) {
    const auto eq = kv.find('=');
    const std::string k = kv.substr(0, eq), v = kv.substr(eq + 1);
    if (k == "name") throw ConfigError("--param", "the method is chosen with --method, not --param name=...");
    if (o.params.contains(k)) throw ConfigError("--param", "'" + k + "' is given twice");
    json parsed;
    try {
      parsed = json::parse(v);
    } catch (const json::exception&) {
      parsed = v;
    }
    o.params[k] = parsed;
  }
  return o;
}

}  // namespace

CommandSpec deconvolve_command_spec(const Registry& registry) {
  return {"deconvolve",
          {},
          "  Deconvolves the system A x = b with a registered deconvolver (the experiments' strategies) and prints\n"
          "  one JSON object: the resolved method, status, statistics, cost, the relative error when the truth is\n"
          "  given, and the solution (inline, or the file of --out).",
          {{"--matrix", "A.mtx", "the operator A (Matrix Market, coordinate or array)", false, true},
           {"--rhs", "b.mtx", "the data b (Matrix Market vector)", false, true},
           {"--x-true", "x.mtx", "the true solution, for the relative error"},
           {"--method", "NAME", "the deconvolver: " + registry.deconvolvers.known_names(), false, true},
           {"--param", "k=v",
            "a deconvolver parameter (closurelab list deconvolver); v is parsed as JSON when it can be\n"
            "(numbers, true/false), else a string; repeatable",
            true, false, ValueForm::key_value},
           {"--noise-level", "d", "absolute noise level ||b - b_exact||_2 for the discrepancy principle", false, false,
            ValueForm::number_nonneg},
           {"--out", "x.mtx", "write the solution there (Matrix Market) instead of inline"}},
          "  Exit codes: 0 solved, 1 a numerical failure or a write failed, 2 bad input."};
}

int run_deconvolve_command(int argc, char** argv, const Registry& registry) {
  if (wants_help(deconvolve_command_spec(registry), argc, argv)) {
    std::cout << usage(deconvolve_command_spec(registry));
    return 0;
  }
  try {
    const Options o = parse(argc, argv, registry);
    json config = o.params;
    config["name"] = o.method;
    json resolved;
    auto d = registry.deconvolvers.create(config, "/method", &resolved);

    const MatrixMarketData m = read_matrix_market(o.matrix);
    const ForwardOperator a = m.coordinate ? ForwardOperator::from_sparse(m.sparse) : ForwardOperator::from_dense(m.dense);
    const Eigen::VectorXd b = read_matrix_market_vector(o.rhs);
    if (b.size() != a.rows())
      throw ConfigError(o.rhs, "right-hand side has " + std::to_string(b.size()) + " entries but the matrix has " +
                                   std::to_string(a.rows()) + " rows");
    Eigen::VectorXd x_true;
    if (!o.x_true.empty()) {
      x_true = read_matrix_market_vector(o.x_true);
      if (x_true.size() != a.cols())
        throw ConfigError(o.x_true, "true solution has " + std::to_string(x_true.size()) +
                                        " entries but the matrix has " + std::to_string(a.cols()) + " columns");
    }
    d->setup(a);
    const DeconvolutionResult r = d->solve(b, o.noise_level);

    json out = r.to_json();
    out["method"] = resolved;
    out["matrix"] = {{"file", o.matrix},
                     {"rows", a.rows()},
                     {"cols", a.cols()},
                     {"storage", to_string(a.storage())}};
    out["rhs"] = o.rhs;
    out["noise_level"] = o.noise_level;
    if (x_true.size() > 0) {
      const double nt = robust_norm(x_true);  // without overflow: data of 1e200 have a finite relative error
      out["relative_error"] = nt > 0 && r.x.allFinite() ? json(robust_norm(r.x - x_true) / nt) : json(nullptr);
    }
    if (!o.out.empty()) {
      try {
        write_matrix_market(o.out, Eigen::MatrixXd(r.x));
      } catch (const std::exception& e) {
        // Nothing half-written is left behind as if it were the solution (a full disk leaves a 0-byte file).
        std::error_code ec;
        if (std::filesystem::is_regular_file(o.out, ec)) std::filesystem::remove(o.out, ec);
        std::cerr << "error: cannot write the solution to '" << o.out << "': " << e.what() << "\n";
        return 1;
      }
      out["solution_file"] = o.out;
    } else {
      std::vector<double> xs(r.x.data(), r.x.data() + r.x.size());
      for (auto& v : xs)
        if (!std::isfinite(v)) v = std::nan("");
      out["solution_file"] = nullptr;
      out["x"] = r.x.allFinite() ? json(xs) : json(nullptr);
    }
    std::cout << out.dump(2) << "\n";
    std::cout.flush();
    if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout)) {
      std::cerr << "error: cannot write the result to standard output: " << std::strerror(errno) << "\n";
      return 1;
    }
    if (!r.stats.note.empty()) std::cerr << "warning: " << r.stats.note << "\n";  // also in stats.note
    if (r.status == DeconvolutionStatus::numerical_issue) {
      std::cerr << "error: numerical failure: " << r.stats.message << "\n";
      return 1;  // the result is printed, but it is not a solution
    }
    return 0;
  } catch (const UsageError& e) {
    std::cerr << "error: " << e.what() << "\n" << e.usage_lines();
    return 2;
  } catch (const ConfigError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const NumericalError& e) {
    std::cerr << "error: numerical failure: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace closurelab
