// `closurelab deconvolve --matrix A.mtx --rhs b.mtx [--x-true x.mtx] --method NAME [--param k=v ...]
//                        [--noise-level d] [--out x.mtx]`
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

namespace closurelab {

namespace {

struct Options {
  std::string matrix, rhs, x_true, method, out;
  json params = json::object();
  double noise_level = 0.0;
};

const char* usage_text =
    "usage: closurelab deconvolve --matrix A.mtx --rhs b.mtx [--x-true x.mtx] --method NAME [--param k=v ...]\n"
    "                             [--noise-level d] [--out x.mtx]\n"
    "  --noise-level d  absolute noise level ||b - b_exact||_2 for the discrepancy principle\n"
    "  --param k=v      a deconvolver parameter; v is parsed as JSON when it can be (numbers, true/false), else a string\n";

Options parse(int argc, char** argv, const Registry& registry) {
  Options o;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw ConfigError(a, "missing value");
      return argv[++i];
    };
    if (a == "--matrix") o.matrix = value();
    else if (a == "--rhs") o.rhs = value();
    else if (a == "--x-true") o.x_true = value();
    else if (a == "--method") o.method = value();
    else if (a == "--out") o.out = value();
    else if (a == "--noise-level") {
      const std::string v = value();
      char* end = nullptr;
      o.noise_level = std::strtod(v.c_str(), &end);
      // strtod also reads hexadecimal ("0x10" = 16) and "inf"/"nan": a decimal number only.
      const bool decimal = v.find_first_not_of("0123456789.eE+-") == std::string::npos;
      if (!decimal || end == v.c_str() || *end != '\0' || !std::isfinite(o.noise_level) || o.noise_level < 0)
        throw ConfigError("--noise-level", "expected a finite number >= 0, got '" + v + "'");
    } else if (a == "--param") {
      const std::string kv = value();
      const auto eq = kv.find('=');
      if (eq == std::string::npos || eq == 0) throw ConfigError("--param", "expected k=v, got '" + kv + "'");
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
    } else {
      throw ConfigError(a, "unknown option; valid: --matrix, --rhs, --x-true, --method, --param, --noise-level, --out, --help");
    }
  }
  if (o.matrix.empty()) throw ConfigError("--matrix", "required");
  if (o.rhs.empty()) throw ConfigError("--rhs", "required");
  if (o.method.empty()) throw ConfigError("--method", "required; known: " + registry.deconvolvers.known_names());
  return o;
}

}  // namespace

int run_deconvolve_command(int argc, char** argv, const Registry& registry) {
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::cout << usage_text << "  methods: " << registry.deconvolvers.known_names()
                << " (parameters: closurelab list deconvolver)\n";
      return 0;
    }
    if (a == "--matrix" || a == "--rhs" || a == "--x-true" || a == "--method" || a == "--out" || a == "--param" ||
        a == "--noise-level")
      ++i;  // skip the option's value
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
    if (r.status == DeconvolutionStatus::numerical_issue) {
      std::cerr << "error: numerical failure: " << r.stats.message << "\n";
      return 1;  // the result is printed, but it is not a solution
    }
    return 0;
  } catch (const ConfigError& e) {
    std::cerr << "error: " << e.what() << "\n" << usage_text;
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
