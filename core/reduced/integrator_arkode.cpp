// The SUNDIALS ARKODE integrators (integrator.hpp): arkode_erk (ERKStep, adaptive explicit Runge–Kutta with error
// control, or forward Euler at the model's step) and arkode_imex (ARKStep, additive Runge–Kutta: the model's stiff
// part implicit, solved by Newton with matrix-free GMRES, the rest explicit). Each instance owns its SUNDIALS
// context, state vector, linear solver and integrator memory (freed by RAII); a step() integrates the state from
// 0 to dt (a stop time at dt: ARKODE lands on it), then resets the held entries. ARKODE 6.4 returns the state at
// a stop time through its interpolation module: the Lagrange one is exact at the step's end (basis 1 and 0), where
// the default Hermite one returned a state that was not the step's (measured on forward Euler). ARKODE evaluates
// the rate once more at each step's end (the next step's first stage), which the reset of the next step discards:
// forward_euler through ARKODE costs two rate evaluations a step where `explicit` costs one.
#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_erkstep.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <type_traits>

#include "core/reduced/integrator.hpp"

namespace closurelab {

namespace {

struct ContextFree {
  void operator()(SUNContext c) const { SUNContext_Free(&c); }
};
struct VectorFree {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct LinearSolverFree {
  void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); }
};
using ContextPtr = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextFree>;
using VectorPtr = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorFree>;
using LinearSolverPtr = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverFree>;
struct MatrixFree {
  void operator()(SUNMatrix m) const { SUNMatDestroy(m); }
};
using MatrixPtr = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixFree>;

// A SUNDIALS direct linear solver on Eigen's partial-pivoting LU: setup factors the matrix ARKODE formed
// (I − γ J, dense, column-major as Eigen's), solve back-substitutes. Eigen's blocked LU is several times faster than
// SUNDIALS' own dense one on the model's ~10³ unknowns. The content (the factors) is owned by the caller.
struct EigenLU {
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  long factorizations = 0;
};
SUNLinearSolver make_eigen_lu_solver(SUNContext context, EigenLU* content) {
  SUNLinearSolver s = SUNLinSolNewEmpty(context);
  if (!s) return nullptr;
  s->content = content;
  s->ops->gettype = [](SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; };
  s->ops->getid = [](SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; };
  s->ops->setup = [](SUNLinearSolver self, SUNMatrix a) -> int {
    auto* c = static_cast<EigenLU*>(self->content);
    const auto n = static_cast<Eigen::Index>(SUNDenseMatrix_Rows(a));
    c->lu.compute(Eigen::Map<const Eigen::MatrixXd>(SUNDenseMatrix_Data(a), n, n));
    ++c->factorizations;
    return 0;
  };
  s->ops->solve = [](SUNLinearSolver self, SUNMatrix, N_Vector x, N_Vector b, realtype) -> int {
    auto* c = static_cast<EigenLU*>(self->content);
    const auto n = static_cast<Eigen::Index>(N_VGetLength(b));
    Eigen::Map<Eigen::VectorXd> out(N_VGetArrayPointer(x), n);
    out = c->lu.solve(Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(b), n));
    return out.allFinite() ? 0 : SUNLS_PACKAGE_FAIL_REC;  // a singular I − γ J: ARKODE retries with a smaller step
  };
  s->ops->free = [](SUNLinearSolver self) -> int {
    self->content = nullptr;  // not ours
    SUNLinSolFreeEmpty(self);
    return 0;
  };
  return s;
}

// ARKODE's name of a return flag (the library allocates it).
std::string flag_name(char* (*name_of)(long int), int flag) {  // NOLINT
  char* s = name_of(flag);
  std::string out = s ? s : "ARK_UNKNOWN";
  std::free(s);  // NOLINT: allocated by SUNDIALS with malloc
  return out;
}

using RateFn = RateFunction;
using FlagNamer = char* (*)(long int);  // ERKStepGetReturnFlagName or ARKStepGetReturnFlagName

// What both integrators share: the context, the state vector, the integrator memory, the model's rate while a step
// runs, and what went wrong (the model's issue, or ARKODE's message).
class ArkodeIntegrator : public Integrator {
 public:
  ArkodeIntegrator(double rtol, double atol, long max_steps) : rtol_(rtol), atol_(atol), max_steps_(max_steps) {
    SUNContext c = nullptr;
    if (SUNContext_Create(nullptr, &c) != 0 || !c) throw std::runtime_error("SUNDIALS: SUNContext_Create failed");
    context_.reset(c);
  }
  ~ArkodeIntegrator() override = default;  // the derived class frees its memory first

  bool step(const CoarseRate& f, double dt, Eigen::VectorXd& u, std::string& issue) override {
    if (!(dt > 0.0) || !std::isfinite(dt)) {
      issue = "ARKODE: the step must be positive and finite (dt = " + std::to_string(dt) + ")";
      return false;
    }
    rate_ = &f;
    rate_issue_.clear();
    message_.clear();
    const bool split = static_cast<bool>(f.stiff);
    if (!memory() || n_ != u.size() || split != split_) {
      free_memory();
      n_ = u.size();
      split_ = split;
      state_.reset(N_VNew_Serial(static_cast<sunindextype>(n_), context_.get()));
      if (!state_) return failed("N_VNew_Serial failed", issue);
      copy_in(u);
      const std::string why = create(split);
      if (!why.empty()) return failed(why, issue);
    }
    copy_in(u);
    int flag = reset_and_stop(dt);
    if (flag < 0) return sundials_failed(flag, issue);
    double t = 0.0;
    flag = evolve(dt, t);
    rate_ = nullptr;
    if (flag < 0) {
      sundials_failed(flag, issue);
      free_memory();  // after an unrecoverable failure start afresh
      return false;
    }
    const Eigen::Map<const Eigen::VectorXd> y(N_VGetArrayPointer(state_.get()), n_);
    u = y;
    hold_entries(f, u);
    if (!u.allFinite()) {
      issue = "ARKODE: the step is not finite";
      return false;
    }
    return true;
  }

  void reset() override { free_memory(); }

 protected:
  // The integrator memory (null until the first step).
  virtual void* memory() const = 0;
  virtual void free_memory() = 0;
  // Creates the memory on state_ (split: the model offers a stiff part); "" or what failed.
  virtual std::string create(bool split) = 0;
  // Reset to t = 0 at the state, stop time dt (and what the step needs of dt); an ARKODE flag.
  virtual int reset_and_stop(double dt) = 0;
  virtual int evolve(double tout, double& t) = 0;
  virtual FlagNamer flag_namer() const = 0;

  // The model's rate `fn` at y into ydot, its held entries zero; ARKODE's convention: 0, or -1 (unrecoverable: the
  // model's issue kept for the report).
  int evaluate(const RateFn& fn, N_Vector y, N_Vector ydot) {
    u_ = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(y), n_);
    std::string why;
    if (!fn(u_, r_, why)) {
      rate_issue_ = why.empty() ? "the model's rate failed" : why;
      return -1;
    }
    if (r_.size() != n_) {
      rate_issue_ = "the model's rate has " + std::to_string(r_.size()) + " entries, the state " + std::to_string(n_);
      return -1;
    }
    if (rate_->held)
      for (Eigen::Index k = 0; k < n_; ++k)
        if ((*rate_->held)[static_cast<std::size_t>(k)]) r_[k] = 0.0;
    Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(ydot), n_) = r_;
    return 0;
  }
  // The whole rate, or the split's parts.
  static int full_rate(realtype, N_Vector y, N_Vector ydot, void* self) {
    auto* me = static_cast<ArkodeIntegrator*>(self);
    return me->evaluate(me->rate_->at, y, ydot);
  }
  static int stiff_rate(realtype, N_Vector y, N_Vector ydot, void* self) {
    auto* me = static_cast<ArkodeIntegrator*>(self);
    return me->evaluate(me->rate_->stiff, y, ydot);
  }
  static int nonstiff_rate(realtype, N_Vector y, N_Vector ydot, void* self) {
    auto* me = static_cast<ArkodeIntegrator*>(self);
    if (me->rate_->nonstiff) return me->evaluate(me->rate_->nonstiff, y, ydot);
    // at − stiff: one call of each.
    const int a = me->evaluate(me->rate_->stiff, y, ydot);
    if (a != 0) return a;
    const Eigen::VectorXd stiff = me->r_;
    const int b = me->evaluate(me->rate_->at, y, ydot);
    if (b != 0) return b;
    Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(ydot), me->n_) = me->r_ - stiff;
    return 0;
  }
  // ARKODE's error and warning messages, kept (not printed); reported with a failure.
  static void on_message(int code, const char* module, const char* function, char* msg, void* self) {
    if (code >= 0) return;  // warnings: the step went on
    auto* me = static_cast<ArkodeIntegrator*>(self);
    me->message_ = std::string(module ? module : "") + "::" + (function ? function : "") + ": " + (msg ? msg : "");
  }

  bool failed(const std::string& why, std::string& issue) {
    issue = "ARKODE: " + why;
    rate_ = nullptr;
    free_memory();
    return false;
  }
  bool sundials_failed(int flag, std::string& issue) {
    issue = "ARKODE " + flag_name(flag_namer(), flag);
    if (!rate_issue_.empty()) issue += ": " + rate_issue_;
    else if (!message_.empty()) issue += ": " + message_;
    rate_ = nullptr;
    return false;
  }

  double rtol_, atol_;
  long max_steps_;
  ContextPtr context_;
  VectorPtr state_;
  Eigen::Index n_ = -1;
  bool split_ = false;
  const CoarseRate* rate_ = nullptr;
  std::string rate_issue_, message_;

 private:
  void copy_in(const Eigen::VectorXd& u) { Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(state_.get()), n_) = u; }
  Eigen::VectorXd u_, r_;  // scratch for the rate
};

// ERKStep: an embedded explicit pair with error control, or forward Euler at the fixed step dt.
class ArkodeErk : public ArkodeIntegrator {
 public:
  ArkodeErk(std::string method, double rtol, double atol, long max_steps)
      : ArkodeIntegrator(rtol, atol, max_steps), method_(std::move(method)) {}
  ~ArkodeErk() override { free_memory(); }

 protected:
  void* memory() const override { return mem_; }
  void free_memory() override {
    if (mem_) ERKStepFree(&mem_);
    mem_ = nullptr;
  }
  std::string create(bool) override {
    mem_ = ERKStepCreate(&ArkodeIntegrator::full_rate, 0.0, state_.get(), context_.get());
    if (!mem_) return "ERKStepCreate failed";
    int flag = ERKStepSetUserData(mem_, this);
    if (flag == 0) flag = ERKStepSetErrHandlerFn(mem_, &ArkodeIntegrator::on_message, this);
    if (flag == 0) flag = ERKStepSetInterpolantType(mem_, ARK_INTERP_LAGRANGE);  // exact at the stop time
    if (flag == 0) flag = ERKStepSStolerances(mem_, rtol_, atol_);
    if (flag == 0) flag = ERKStepSetMaxNumSteps(mem_, max_steps_);
    if (flag == 0) {
      if (method_ == "forward_euler") {
        // ARKODE 6.4 has no forward Euler table: one stage, b = 1, no embedding (run at a fixed step).
        realtype c[1] = {0.0}, a[1] = {0.0}, b[1] = {1.0};
        ARKodeButcherTable table = ARKodeButcherTable_Create(1, 1, 0, c, a, b, nullptr);
        if (!table) return "ARKodeButcherTable_Create failed";
        flag = ERKStepSetTable(mem_, table);  // copied
        ARKodeButcherTable_Free(table);
      } else {
        flag = ERKStepSetTableNum(mem_, table_of(method_));
      }
    }
    return flag == 0 ? "" : "setting up ERKStep: " + flag_name(&ERKStepGetReturnFlagName, flag);
  }
  int reset_and_stop(double dt) override {
    int flag = ERKStepReset(mem_, 0.0, state_.get());
    if (flag == 0 && method_ == "forward_euler") flag = ERKStepSetFixedStep(mem_, dt);
    if (flag == 0) flag = ERKStepSetStopTime(mem_, dt);
    return flag;
  }
  int evolve(double tout, double& t) override { return ERKStepEvolve(mem_, tout, state_.get(), &t, ARK_NORMAL); }
  FlagNamer flag_namer() const override { return &ERKStepGetReturnFlagName; }

 private:
  static ARKODE_ERKTableID table_of(const std::string& m) {
    if (m == "heun_euler") return ARKODE_HEUN_EULER_2_1_2;
    if (m == "bogacki_shampine") return ARKODE_BOGACKI_SHAMPINE_4_2_3;
    if (m == "dormand_prince") return ARKODE_DORMAND_PRINCE_7_4_5;
    return ARKODE_ZONNEVELD_5_3_4;
  }
  std::string method_;
  void* mem_ = nullptr;
};

// ARKStep: additive Runge–Kutta, the stiff part by the DIRK table, the rest by the ERK table; no split: the DIRK
// table on the whole rate. The Newton systems (I − γ J) δ = r: by matrix-free GMRES with ARKODE's difference-quotient
// J·v (linear_solver gmres), or (dense) by Eigen's LU of I − γ J with J the implicit part's Jacobian probed once with
// unit vectors (the implicit part affine in u: a closure with fixed parameters), refactored only when ARKODE's
// setup asks (γ changed by more than 20 %, or 20 steps passed).
class ArkodeImex : public ArkodeIntegrator {
 public:
  ArkodeImex(std::string method, double rtol, double atol, long max_steps, int krylov_dim, bool dense)
      : ArkodeIntegrator(rtol, atol, max_steps), method_(std::move(method)), krylov_dim_(krylov_dim), dense_(dense) {}
  ~ArkodeImex() override { free_memory(); }
  bool needs_linear_closure() const override { return dense_; }

 protected:
  void* memory() const override { return mem_; }
  void free_memory() override {
    if (mem_) ARKStepFree(&mem_);
    mem_ = nullptr;
    solver_.reset();  // after the memory that uses it
    matrix_.reset();
  }
  std::string create(bool split) override {
    mem_ = ARKStepCreate(split ? &ArkodeIntegrator::nonstiff_rate : nullptr,
                         split ? &ArkodeIntegrator::stiff_rate : &ArkodeIntegrator::full_rate, 0.0, state_.get(),
                         context_.get());
    if (!mem_) return "ARKStepCreate failed";
    if (dense_) {
      const std::string why = probe_implicit_part(split);
      if (!why.empty()) return why;
      matrix_.reset(SUNDenseMatrix(static_cast<sunindextype>(n_), static_cast<sunindextype>(n_), context_.get()));
      if (!matrix_) return "SUNDenseMatrix failed";
      solver_.reset(make_eigen_lu_solver(context_.get(), &lu_));
      if (!solver_) return "SUNLinSolNewEmpty failed";
    } else {
      const int maxl = static_cast<int>(std::min<Eigen::Index>(krylov_dim_, std::max<Eigen::Index>(n_, 1)));
      solver_.reset(SUNLinSol_SPGMR(state_.get(), SUN_PREC_NONE, maxl, context_.get()));
      if (!solver_) return "SUNLinSol_SPGMR failed";
    }
    int flag = ARKStepSetUserData(mem_, this);
    if (flag == 0) flag = ARKStepSetErrHandlerFn(mem_, &ArkodeIntegrator::on_message, this);
    if (flag == 0) flag = ARKStepSetInterpolantType(mem_, ARK_INTERP_LAGRANGE);  // exact at the stop time
    if (flag == 0) flag = ARKStepSStolerances(mem_, rtol_, atol_);
    if (flag == 0) flag = ARKStepSetMaxNumSteps(mem_, max_steps_);
    if (flag == 0) flag = ARKStepSetLinearSolver(mem_, solver_.get(), matrix_.get());  // null matrix: DQ J·v
    if (flag == 0 && dense_) flag = ARKStepSetJacFn(mem_, &ArkodeImex::probed_jacobian);
    if (flag == 0) {
      const auto [dirk, erk] = tables_of(method_);
      flag = ARKStepSetTableNum(mem_, dirk, split ? erk : ARKODE_ERK_NONE);
    }
    return flag == 0 ? "" : "setting up ARKStep: " + flag_name(&ARKStepGetReturnFlagName, flag);
  }
  int reset_and_stop(double dt) override {
    int flag = ARKStepReset(mem_, 0.0, state_.get());
    if (flag == 0) flag = ARKStepSetStopTime(mem_, dt);
    return flag;
  }
  int evolve(double tout, double& t) override { return ARKStepEvolve(mem_, tout, state_.get(), &t, ARK_NORMAL); }
  FlagNamer flag_namer() const override { return &ARKStepGetReturnFlagName; }

 private:
  static std::pair<ARKODE_DIRKTableID, ARKODE_ERKTableID> tables_of(const std::string& m) {
    if (m == "ark324") return {ARKODE_ARK324L2SA_DIRK_4_2_3, ARKODE_ARK324L2SA_ERK_4_2_3};
    if (m == "ark548") return {ARKODE_ARK548L2SA_DIRK_8_4_5, ARKODE_ARK548L2SA_ERK_8_4_5};
    return {ARKODE_ARK436L2SA_DIRK_6_3_4, ARKODE_ARK436L2SA_ERK_6_3_4};
  }
  // The implicit part's Jacobian (the stiff part, or the whole rate without a split), probed at the state's size;
  // "" or why not.
  std::string probe_implicit_part(bool split) {
    Eigen::VectorXd offset, base;
    std::string issue;
    if (probe_affine(split ? rate_->stiff : rate_->at, *rate_, n_, jacobian_, offset, base, issue)) {
      if (rate_->held)  // the held entries' rate is zero during a step
        for (Eigen::Index k = 0; k < n_; ++k)
          if ((*rate_->held)[static_cast<std::size_t>(k)]) jacobian_.row(k).setZero();
      return "";
    }
    if (!issue.empty()) return "probing the implicit part's Jacobian: " + issue;
    return std::string("linear_solver dense needs the implicit part affine in the state (a closure with fixed "
                       "parameters") + (split ? "" : "; the model offers no split, so that is its whole rate") +
           "); this one is not: use linear_solver gmres";
  }
  static int probed_jacobian(realtype, N_Vector, N_Vector, SUNMatrix jac, void* self, N_Vector, N_Vector, N_Vector) {
    auto* me = static_cast<ArkodeImex*>(self);
    Eigen::Map<Eigen::MatrixXd>(SUNDenseMatrix_Data(jac), me->n_, me->n_) = me->jacobian_;
    return 0;
  }

  std::string method_;
  int krylov_dim_;
  bool dense_;
  Eigen::MatrixXd jacobian_;
  EigenLU lu_;
  MatrixPtr matrix_;
  LinearSolverPtr solver_;
  void* mem_ = nullptr;
};

ParamSchema tolerance_schema() {
  return {number_param("rtol", 1e-6, "relative tolerance of ARKODE's local error control", 0.0, 1.0, true),
          number_param("atol", 1e-12, "absolute tolerance of ARKODE's local error control (in the state's units)",
                       0.0, {}, true),
          integer_param("max_steps", 10000, "ARKODE's internal steps allowed in one coarse step before it fails", 1,
                        {}, IntegerKind::int64)};
}

}  // namespace

void register_arkode_integrators(Registry& r) {
  ParamSchema erk = tolerance_schema();
  erk.insert(erk.begin(),
             string_param("method", "zonneveld",
                          "ARKODE's explicit table: zonneveld (ZONNEVELD_5_3_4, order 4 with an embedded 3, ARKODE's "
                          "default), heun_euler (2(1)), bogacki_shampine (3(2)), dormand_prince (5(4)), each with "
                          "error control; forward_euler: one stage at a fixed step equal to the model's dt, no error "
                          "control (rtol and atol unused), the paper's step through ARKODE",
                          {"zonneveld", "heun_euler", "bogacki_shampine", "dormand_prince", "forward_euler"}));
  r.integrators.add({"arkode_erk",
                     "SUNDIALS ARKODE ERKStep: adaptive explicit Runge-Kutta with local error control from t to t + dt "
                     "(internal steps as needed, landing on t + dt), held nodes at rate zero then reset",
                     erk},
                    [](const json& p) {
                      return std::make_unique<ArkodeErk>(p.at("method").get<std::string>(), p.at("rtol").get<double>(),
                                                         p.at("atol").get<double>(), p.at("max_steps").get<long>());
                    });
  ParamSchema imex = tolerance_schema();
  imex.insert(imex.begin(),
              string_param("method", "ark436",
                           "ARKODE's additive Runge-Kutta pair (Kennedy & Carpenter): ark436 (ARK4(3)6L[2]SA, "
                           "ARKODE's default), ark324 (ARK3(2)4L[2]SA), ark548 (ARK5(4)8L[2]SA); without a split its "
                           "DIRK table alone",
                           {"ark436", "ark324", "ark548"}));
  imex.push_back(string_param(
      "linear_solver", "gmres",
      "how the Newton systems (I - gamma J) d = r are solved: gmres (matrix-free GMRES on ARKODE's difference-quotient "
      "J v, no preconditioner; any implicit part), or dense (J the implicit part's Jacobian probed once with unit "
      "vectors, I - gamma J factored by Eigen's LU when ARKODE's setup asks, i.e. when gamma changed by over 20 % or "
      "after 20 steps; needs the implicit part affine in the state, a closure with fixed parameters, and costs one "
      "rate evaluation per unknown)",
      {"gmres", "dense"}));
  imex.push_back(integer_param("krylov_dim", 20,
                               "GMRES Krylov dimension of the Newton solve (at most the state size; linear_solver "
                               "gmres)",
                               1, 1000));
  r.integrators.add({"arkode_imex",
                     "SUNDIALS ARKODE ARKStep IMEX with error control: the model's stiff (viscous) part implicit, "
                     "solved by Newton with matrix-free GMRES (difference-quotient J v, no preconditioner) or with the "
                     "probed Jacobian's LU (linear_solver dense), the rest explicit; a model that offers no split is "
                     "integrated implicitly whole (a DIRK); with gmres it needs no affine rate",
                     imex},
                    [](const json& p) {
                      return std::make_unique<ArkodeImex>(p.at("method").get<std::string>(), p.at("rtol").get<double>(),
                                                          p.at("atol").get<double>(), p.at("max_steps").get<long>(),
                                                          p.at("krylov_dim").get<int>(),
                                                          p.at("linear_solver").get<std::string>() == "dense");
                    });
}

}  // namespace closurelab
