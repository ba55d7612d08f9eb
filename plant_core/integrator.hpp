#pragma once
// CVODE adapter around model::derivative: integrates one tick [t, t + dt] with the inputs
// held (zero-order hold). BDF with a dense direct solver; the integrator is re-initialised
// at each tick because the inputs jump there. No DDS, no clock: testable alone.
#include <memory>

#include "model/dynamics.hpp"

namespace maptr::plant_core {

struct IntegratorOptions {
  double rtol = 1e-8;
  double atol_scale = 1e-9;  ///< absolute tolerance = atol_scale * max(1, typical magnitude)
  long max_steps = 100000;   ///< per tick
};

class CvodeIntegrator {
 public:
  CvodeIntegrator(model::RobotParams p, IntegratorOptions o = {});
  ~CvodeIntegrator();
  CvodeIntegrator(const CvodeIntegrator&) = delete;
  CvodeIntegrator& operator=(const CvodeIntegrator&) = delete;

  /// Advances state from t to t + dt with inputs u held. Throws std::runtime_error on a
  /// CVODE failure (with CVODE's flag).
  void step(model::State& state, const model::Inputs& u, double t, double dt);

  const model::RobotParams& params() const { return p_; }

 public:
  struct Impl;  ///< CVODE handles (defined in the .cpp)

 private:
  model::RobotParams p_;
  IntegratorOptions o_;
  std::unique_ptr<Impl> impl_;
};

/// Classic fixed-step RK4 with the same inputs held (reference for tests and benches).
void rk4_step(const model::RobotParams& p, const model::Inputs& u, model::State& x, double dt, int substeps);

}  // namespace maptr::plant_core
