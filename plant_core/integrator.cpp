#include "plant_core/integrator.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <stdexcept>
#include <string>

namespace maptr::plant_core {

struct CvodeIntegrator::Impl {
  SUNContext ctx = nullptr;
  void* mem = nullptr;
  N_Vector y = nullptr;
  N_Vector abstol = nullptr;
  SUNMatrix a = nullptr;
  SUNLinearSolver ls = nullptr;
  const model::RobotParams* p = nullptr;
  const model::Inputs* u = nullptr;
  bool initialised = false;

  ~Impl() {
    if (mem) CVodeFree(&mem);
    if (ls) SUNLinSolFree(ls);
    if (a) SUNMatDestroy(a);
    if (y) N_VDestroy(y);
    if (abstol) N_VDestroy(abstol);
    if (ctx) SUNContext_Free(&ctx);
  }
};

namespace {

int rhs(realtype, N_Vector y, N_Vector ydot, void* user) {
  auto* impl = static_cast<CvodeIntegrator::Impl*>(user);
  model::derivative(*impl->p, *impl->u, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
  return 0;
}

void check(int flag, const char* what) {
  if (flag < 0)
    throw std::runtime_error(std::string("CVODE ") + what + " failed with flag " + std::to_string(flag));
}

}  // namespace

CvodeIntegrator::CvodeIntegrator(model::RobotParams p, IntegratorOptions o)
    : p_(std::move(p)), o_(o), impl_(std::make_unique<Impl>()) {
  auto& im = *impl_;
  check(SUNContext_Create(nullptr, &im.ctx), "SUNContext_Create");
  im.y = N_VNew_Serial(model::kStateSize, im.ctx);
  im.abstol = N_VNew_Serial(model::kStateSize, im.ctx);
  if (!im.y || !im.abstol) throw std::runtime_error("CVODE: cannot allocate vectors");
  double* at = N_VGetArrayPointer(im.abstol);
  for (int i = 0; i < model::kStateSize; ++i) at[i] = o_.atol_scale;
  // Ledgers grow large (kJ, km): give them absolute tolerances to match their scale.
  for (int i : {model::kEnergyL, model::kEnergyR, model::kLossJoule, model::kLossMech, model::kLossEmf})
    at[i] = o_.atol_scale * 1e3;
  for (int i : {model::kX, model::kY, model::kPathL, model::kPathR, model::kDistance, model::kChargeL,
                model::kChargeR})
    at[i] = o_.atol_scale * 1e2;
  im.mem = CVodeCreate(CV_BDF, im.ctx);
  if (!im.mem) throw std::runtime_error("CVODE: CVodeCreate failed");
  check(CVodeInit(im.mem, rhs, 0.0, im.y), "CVodeInit");
  check(CVodeSVtolerances(im.mem, o_.rtol, im.abstol), "CVodeSVtolerances");
  check(CVodeSetUserData(im.mem, &im), "CVodeSetUserData");
  check(CVodeSetMaxNumSteps(im.mem, o_.max_steps), "CVodeSetMaxNumSteps");
  im.a = SUNDenseMatrix(model::kStateSize, model::kStateSize, im.ctx);
  im.ls = SUNLinSol_Dense(im.y, im.a, im.ctx);
  if (!im.a || !im.ls) throw std::runtime_error("CVODE: cannot create the dense linear solver");
  check(CVodeSetLinearSolver(im.mem, im.ls, im.a), "CVodeSetLinearSolver");
  im.p = &p_;
}

CvodeIntegrator::~CvodeIntegrator() = default;

void CvodeIntegrator::step(model::State& x, const model::Inputs& u, double t, double dt) {
  if (!(dt > 0.0)) throw std::invalid_argument("dt = " + std::to_string(dt) + ": must be positive");
  auto& im = *impl_;
  im.u = &u;
  double* y = N_VGetArrayPointer(im.y);
  for (int i = 0; i < model::kStateSize; ++i) y[i] = x[i];
  check(CVodeReInit(im.mem, t, im.y), "CVodeReInit");
  check(CVodeSetStopTime(im.mem, t + dt), "CVodeSetStopTime");
  realtype t_reached = t;
  check(CVode(im.mem, t + dt, im.y, &t_reached, CV_NORMAL), "CVode");
  for (int i = 0; i < model::kStateSize; ++i) x[i] = y[i];
  im.u = nullptr;
}

void rk4_step(const model::RobotParams& p, const model::Inputs& u, model::State& x, double dt, int substeps) {
  const double h = dt / substeps;
  model::State k1, k2, k3, k4, tmp;
  for (int s = 0; s < substeps; ++s) {
    model::derivative(p, u, x.data(), k1.data());
    for (int i = 0; i < model::kStateSize; ++i) tmp[i] = x[i] + 0.5 * h * k1[i];
    model::derivative(p, u, tmp.data(), k2.data());
    for (int i = 0; i < model::kStateSize; ++i) tmp[i] = x[i] + 0.5 * h * k2[i];
    model::derivative(p, u, tmp.data(), k3.data());
    for (int i = 0; i < model::kStateSize; ++i) tmp[i] = x[i] + h * k3[i];
    model::derivative(p, u, tmp.data(), k4.data());
    for (int i = 0; i < model::kStateSize; ++i) x[i] += h / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  }
}

}  // namespace maptr::plant_core
