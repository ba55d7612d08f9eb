// Agent faults without a fleet: each motor fault's current and torque against its closed form
// (model/motor_fault.hpp, model/dynamics.hpp), the detector's residuals and diagnosis on samples
// the motor model makes for healthy and faulty drives (control/diagnosis.hpp), isolation in
// GroupCore, the plant's fault book (plant_core/fault_book.hpp) and an agent's software faults
// (agent/misbehaviour.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "agent/misbehaviour.hpp"
#include "control/diagnosis.hpp"
#include "control/group_core.hpp"
#include "model/dynamics.hpp"
#include "model/motor.hpp"
#include "model/motor_fault.hpp"
#include "plant_core/fault_book.hpp"

namespace {

using namespace maptr;
using model::MotorFault;
using model::MotorFaultKind;

model::MotorParams motor() { return model::MotorParams{}; }
model::DriverParams bidirectional() {
  model::DriverParams d;
  d.bidirectional = true;
  return d;
}

/// Torque of one motor alone on a side (the others absent), N m.
double torque_of(const MotorFault& f, double volts, double phidot, const model::DriverParams& d) {
  return model::side_load(motor(), d, {volts}, {1}, phidot, {f}).torque_Nm;
}

TEST(MotorFault, HealthyFaultListLeavesTheSideBitForBit) {
  const model::DriverParams d = bidirectional();
  const std::vector<double> v = {6.0, -2.0, 11.0};
  const std::vector<uint8_t> act = {1, 1, 0};
  const auto a = model::side_load(motor(), d, v, act, 40.0);
  const auto b = model::side_load(motor(), d, v, act, 40.0, std::vector<MotorFault>(3));
  EXPECT_EQ(a.torque_Nm, b.torque_Nm);
  EXPECT_EQ(a.current_A, b.current_A);
  EXPECT_EQ(a.joule_W, b.joule_W);
}

TEST(MotorFault, TorqueFactorScalesTorqueAndBackEmfConstants) {
  const model::MotorParams m = motor();
  const double F = 0.5, V = 12.0, w = 100.0;
  const double I = (V - F * m.back_emf_Vs * w) / m.resistance_ohm;  // closed form
  const double sgn = model::smooth_sign(w, m.friction_sign_scale_rad_s);
  // K_T I_0 (friction) is kept: K_T F (I - I_0 sgn / F) - b w.
  const double tau = F * m.torque_constant_NmA * I - m.torque_constant_NmA * m.no_load_current_A * sgn -
                     m.viscous_Nms * w;
  EXPECT_NEAR(torque_of({MotorFaultKind::kTorque, F}, V, w, bidirectional()), tau, 1e-12);
  const model::Winding wd = model::winding({MotorFaultKind::kTorque, F}, true, V, false, -24, 24);
  EXPECT_NEAR(model::winding_current(m, bidirectional(), {MotorFaultKind::kTorque, F}, wd, w), I, 1e-12);
}

TEST(MotorFault, ResistanceFactorScalesTheWindingsResistance) {
  const model::MotorParams m = motor();
  const double F = 3.0, V = 12.0, w = 100.0;
  const double I = (V - m.back_emf_Vs * w) / (F * m.resistance_ohm);
  const auto s = model::side_load(m, bidirectional(), {V}, {1}, w, {{MotorFaultKind::kResistance, F}});
  EXPECT_NEAR(s.current_A, I, 1e-12);
  EXPECT_NEAR(s.joule_W, I * I * F * m.resistance_ohm, 1e-12);
}

TEST(MotorFault, ShortBrakesInProportionToSpeedAndDrawsNothing) {
  const model::MotorParams m = motor();
  for (double w : {20.0, 80.0}) {
    const double I = -m.back_emf_Vs * w / m.resistance_ohm;
    const double sgn = model::smooth_sign(w, m.friction_sign_scale_rad_s);
    const double tau = m.torque_constant_NmA * (I - m.no_load_current_A * sgn) - m.viscous_Nms * w;
    const model::Winding wd = model::winding({MotorFaultKind::kShort, 0}, true, 12.0, false, 0, 24);
    const auto s = model::side_load(m, model::DriverParams{}, {wd.voltage_V}, {1}, w, {{MotorFaultKind::kShort, 0}});
    EXPECT_NEAR(s.torque_Nm, tau, 1e-12) << w;
    EXPECT_LT(s.torque_Nm, 0.0);
    EXPECT_EQ(s.current_A, 0.0);  // the battery gives nothing
    EXPECT_EQ(s.power_W, 0.0);
    EXPECT_NEAR(s.joule_W, I * I * m.resistance_ohm, 1e-12);
    EXPECT_NEAR(model::winding_current(m, model::DriverParams{}, {MotorFaultKind::kShort, 0}, wd, w), I, 1e-15);
  }
}

TEST(MotorFault, OpenAndDisconnectedWindingsCarryNothing) {
  const model::Winding open = model::winding({MotorFaultKind::kOpen, 0}, true, 12.0, false, 0, 24);
  EXPECT_FALSE(open.conducts);
  EXPECT_EQ(model::winding_current(motor(), {}, {MotorFaultKind::kOpen, 0}, open, 50.0), 0.0);
  const model::Winding cut = model::winding({MotorFaultKind::kStuck, 20.0}, false, 0.0, true, 0, 24);
  EXPECT_FALSE(cut.conducts);  // a disconnected driver: whatever the fault
  // The open motor's torque is the free-wheeling one.
  EXPECT_EQ(model::side_load(motor(), {}, {0.0}, {0}, 50.0).torque_Nm, model::inactive_torque(motor(), 50.0));
}

TEST(MotorFault, StuckDriverAppliesItsVoltageClampedToItsRange) {
  const model::Winding w = model::winding({MotorFaultKind::kStuck, 12.0}, false, 0.0, false, 0, 24);
  EXPECT_TRUE(w.conducts);
  EXPECT_EQ(w.voltage_V, 12.0);  // even when the agent is idle
  EXPECT_EQ(model::winding({MotorFaultKind::kStuck, 30.0}, true, 5.0, false, 0, 23.5).voltage_V, 23.5);
  const double I = (12.0 - motor().back_emf_Vs * 50.0) / motor().resistance_ohm;
  EXPECT_NEAR(model::winding_current(motor(), {}, {MotorFaultKind::kStuck, 12.0}, w, 50.0), I, 1e-12);
}

// ---- The detector ----

control::DiagnosisConfig diag_config() {
  control::DiagnosisConfig c;
  c.driver = bidirectional();
  c.dt_s = 0.01;
  c.fault_persistence_s = 0.1;
  c.fault_probation_s = 10.0;
  return c;
}

/// A side of 4 agents at a steady speed, each driving at V (+ a slow drift common to all);
/// `fault` says what agent 1's drive really does.
struct Drive {
  MotorFault fault;
  std::string software;  ///< "", "sensor", "erratic", "liar"
  double value = 0.0;
};

control::SideSample sample(long long k, const Drive& d) {
  const model::MotorParams m = motor();
  const model::DriverParams dr = bidirectional();
  control::SideSample s;
  s.phidot = 28.0 + 0.001 * static_cast<double>(k);
  s.phidot_prev = s.phidot - 0.001;
  const double V = 3.0 + 0.002 * static_cast<double>(k);
  for (int j = 0; j < 4; ++j) {
    control::DriveSample a;
    a.drove = true;
    a.drive_V = V;
    a.reported = true;
    a.reported_A = model::armature_current(m, dr, V, s.phidot_prev);
    if (j == 1) {
      if (d.software == "erratic") a.drive_V = V + d.value * agent::seeded_noise(k, 0, j);
      if (d.software == "liar") a.drive_V = 23.0;  // it drives flat out and reports a healthy current
      if (d.software == "sensor") a.reported_A = model::armature_current(m, dr, V, s.phidot_prev + d.value);
      else if (d.software != "liar") a.reported_A = model::armature_current(m, dr, a.drive_V, s.phidot_prev);
    }
    const MotorFault f = j == 1 ? d.fault : MotorFault{};
    const model::Winding w = model::winding(f, a.drove, a.drive_V, false, -23.0, 23.0);
    a.measured_A = static_cast<float>(model::winding_current(m, dr, f, w, s.phidot));
    s.agents.push_back(a);
  }
  return s;
}

/// Ticks a detector through healthy ticks 0..99, then the drive from tick 100 on; returns the
/// flag of agent 1 and the tick it was raised (-1: never) within 100 faulty ticks.
std::pair<control::Diagnosis, long long> diagnose(const Drive& d) {
  control::SideDiagnosis det(4, diag_config());
  for (long long k = 0; k < 200; ++k) {
    const auto changes = det.step(static_cast<double>(k) * 0.01, sample(k, k < 100 ? Drive{} : d));
    for (const auto& c : changes) {
      EXPECT_EQ(c.index, 1) << "a healthy agent flagged at tick " << k;
      if (c.index == 1) return {c.flag, k};
    }
  }
  return {control::Diagnosis::kNone, -1};
}

TEST(Diagnosis, HealthyDrivesRaiseNoFlag) {
  EXPECT_EQ(diagnose(Drive{}).second, -1);
}

TEST(Diagnosis, EachFaultIsFlaggedAfterThePersistenceTimeAsWhatItIs) {
  struct Case {
    Drive drive;
    control::Diagnosis want;
  };
  const std::vector<Case> cases = {
      {{{MotorFaultKind::kOpen, 0}, "", 0}, control::Diagnosis::kOpen},
      {{{MotorFaultKind::kShort, 0}, "", 0}, control::Diagnosis::kShort},
      {{{MotorFaultKind::kTorque, 0.5}, "", 0}, control::Diagnosis::kTorque},
      {{{MotorFaultKind::kResistance, 3.0}, "", 0}, control::Diagnosis::kResistance},
      {{{MotorFaultKind::kStuck, 12.0}, "", 0}, control::Diagnosis::kStuck},
      {{{}, "sensor", 5.0}, control::Diagnosis::kSensor},
      {{{}, "erratic", 2.0}, control::Diagnosis::kErratic},
      {{{}, "liar", 0.0}, control::Diagnosis::kLiar},
  };
  for (const auto& c : cases) {
    const auto [flag, k] = diagnose(c.drive);
    EXPECT_EQ(control::diagnosis_name(flag), std::string(control::diagnosis_name(c.want)))
        << control::diagnosis_name(c.want);
    // Residuals on every tick of the persistence time (10 ticks); jitter: its median over them
    // (more than half of them).
    const long long least = c.want == control::Diagnosis::kErratic ? 100 + 5 : 100 + 9;
    EXPECT_GE(k, least) << "flagged before the persistence time: " << control::diagnosis_name(c.want);
    EXPECT_LE(k, 100 + 20) << control::diagnosis_name(c.want);
  }
}

TEST(Diagnosis, ASingleOutlierIsNotAFault) {
  control::SideDiagnosis det(4, diag_config());
  for (long long k = 0; k < 100; ++k) {
    control::SideSample s = sample(k, Drive{});
    if (k % 5 == 0) s.agents[2].measured_A += 1.0f;  // a glitch every 5th tick: never 10 in a row
    EXPECT_TRUE(det.step(static_cast<double>(k) * 0.01, s).empty()) << k;
  }
}

TEST(Diagnosis, AnIsolatedAgentComesBackAfterItsProbationWhichDoublesAtARelapse) {
  control::SideDiagnosis det(4, diag_config());
  const Drive open{{MotorFaultKind::kOpen, 0}, "", 0};
  std::vector<std::pair<double, control::Diagnosis>> seen;
  for (long long k = 0; k < 4000; ++k) {
    const double t = static_cast<double>(k) * 0.01;
    control::SideSample s = sample(k, open);
    if (det.flags()[1]) s.agents[1].measured_A = 0.0f;  // disconnected
    for (const auto& c : det.step(t, s)) seen.push_back({t, c.flag});
  }
  ASSERT_GE(seen.size(), 4u);
  EXPECT_EQ(seen[0].second, control::Diagnosis::kOpen);
  EXPECT_NEAR(seen[0].first, 0.09, 1e-9);
  EXPECT_EQ(seen[1].second, control::Diagnosis::kNone);
  EXPECT_NEAR(seen[1].first - seen[0].first, 10.0, 0.011);  // probation
  EXPECT_EQ(seen[2].second, control::Diagnosis::kOpen);    // still open: flagged again
  EXPECT_NEAR(seen[3].first - seen[2].first, 20.0, 0.011);  // doubled
}

TEST(GroupCore, AFlaggedAgentIsNeitherCountedNorAssignedAndIsAnnounced) {
  control::GroupConfig c;
  c.mode = control::GroupMode::kAll;
  c.robot.agents = 8;
  control::GroupCore core(0, c);
  control::GroupInput in;
  in.live.assign(4, 1);
  in.active.assign(4, 1);
  in.measured = true;
  const Drive open{{MotorFaultKind::kOpen, 0}, "", 0};
  control::GroupDecision d;
  for (long long k = 0; k < 120; ++k) {
    in.tick = k;
    in.t = static_cast<double>(k) * 0.01;
    in.drives = sample(k, k < 100 ? Drive{} : open);
    d = core.step(in);
    if (k < 109) EXPECT_EQ(d.active, std::vector<uint8_t>({1, 1, 1, 1})) << k;
  }
  EXPECT_EQ(d.active, std::vector<uint8_t>({1, 0, 1, 1}));
  EXPECT_EQ(d.n_live, 3);
  EXPECT_EQ(d.faulty, std::vector<uint8_t>({0, static_cast<uint8_t>(control::Diagnosis::kOpen), 0, 0}));
}

TEST(GroupCore, WithoutMeasurementsNothingIsFlagged) {
  control::GroupConfig c;
  c.mode = control::GroupMode::kAll;
  c.robot.agents = 8;
  control::GroupCore core(0, c);
  control::GroupInput in;
  in.live.assign(4, 1);
  in.active.assign(4, 1);
  for (long long k = 0; k < 50; ++k) {
    in.tick = k;
    in.t = static_cast<double>(k) * 0.01;
    EXPECT_EQ(core.step(in).faulty, std::vector<uint8_t>(4, 0));
  }
}

// ---- The plant's record ----

const char* const kNames[] = {"", "open", "short", "torque", "resistance", "stuck", "sensor", "erratic", "liar"};

TEST(FaultBook, AppliesFaultsAtTheirTickAndRecordsDetectionIsolationAndFalseDetections) {
  plant_core::FaultBook book(
      4, {{200, 0, 3, false, "torque", 0.5}, {400, 0, 3, true, "", 0.0}, {100, 1, 0, false, "liar", 0}});
  book.apply(99, 0.99);
  EXPECT_TRUE(book.records().empty());
  book.apply(100, 1.0);
  EXPECT_FALSE(book.any_motor_fault(1));  // a software fault: no motor fault
  book.apply(200, 2.0);
  EXPECT_EQ(book.motor(0)[3].kind, MotorFaultKind::kTorque);
  EXPECT_EQ(book.motor(0)[3].value, 0.5);
  book.on_flags(0, {0, 0, 0, 3}, 2.1, 0.01, kNames, 9);
  EXPECT_TRUE(book.disconnected(0, 3));
  book.on_flags(0, {0, 1, 0, 3}, 2.5, 0.01, kNames, 9);  // L1: no fault in force
  book.apply(400, 4.0);
  EXPECT_FALSE(book.any_motor_fault(0));
  book.on_flags(0, {0, 0, 0, 0}, 12.1, 0.01, kNames, 9);
  ASSERT_EQ(book.records().size(), 2u);
  const auto& r = book.records()[1];
  EXPECT_EQ(r.target, "L3");
  EXPECT_EQ(r.injected_s, 2.0);
  EXPECT_EQ(*r.detected_s, 2.1);
  EXPECT_DOUBLE_EQ(*r.isolated_s, 2.11);
  EXPECT_EQ(r.diagnosed_mode, "torque");
  EXPECT_EQ(*r.cleared_s, 4.0);
  EXPECT_EQ(*r.readmitted_s, 12.1);
  EXPECT_FALSE(book.records()[0].detected_s.has_value());  // R0's liar: never flagged
  EXPECT_EQ(book.false_detections(), 1);
}

// ---- The agent's software ----

control::AgentInput assigned_input(long long k) {
  control::AgentInput in;
  in.tick = k;
  in.phidot_rad_s = in.phidot_prev_rad_s = 20.0;
  in.phidot_ref_rad_s = in.phidot_ref_prev_rad_s = 28.0;
  in.battery_V = 23.0;
  in.assigned = true;
  in.group_stamp = k - 1;
  in.central_stamp = k - 1;
  return in;
}

TEST(Misbehaviour, EachSoftwareFaultActsFromItsTickUntilItsClear) {
  control::AgentConfig c;
  c.driver = bidirectional();
  agent::FaultyAgent healthy(c, {}, 0, 1);
  agent::FaultyAgent sensor(c, {{10, agent::Misbehaviour::kSensor, 5.0}, {20, agent::Misbehaviour::kNone, 0}}, 0, 1);
  agent::FaultyAgent erratic(c, {{10, agent::Misbehaviour::kErratic, 2.0}}, 0, 1);
  agent::FaultyAgent liar(c, {{10, agent::Misbehaviour::kLiar, 0.0}}, 0, 1);
  for (long long k = 0; k < 30; ++k) {
    const auto in = assigned_input(k);
    const auto h = healthy.step(in), s = sensor.step(in), e = erratic.step(in), l = liar.step(in);
    if (k < 10) {
      EXPECT_EQ(s.voltage_V, h.voltage_V);
      EXPECT_EQ(e.voltage_V, h.voltage_V);
      EXPECT_EQ(l.voltage_V, h.voltage_V);
      continue;
    }
    // The liar drives flat out and reports the healthy agent's current.
    EXPECT_EQ(l.voltage_V, 23.0);
    EXPECT_EQ(l.current_A, h.current_A);
    // Erratic: the same seeded noise in every run, and a truthful current for it.
    EXPECT_NEAR(e.voltage_V, std::clamp(h.voltage_V + 2.0 * agent::seeded_noise(k, 0, 1), -23.0, 23.0), 1e-12);
    EXPECT_EQ(e.current_A, model::armature_current(c.motor, c.driver, e.voltage_V, 20.0));
    // Sensor: it reports the current its voltage gives at the speed it reads.
    if (k < 20) EXPECT_EQ(s.current_A, model::armature_current(c.motor, c.driver, s.voltage_V, 25.0)) << k;
    else EXPECT_EQ(s.current_A, model::armature_current(c.motor, c.driver, s.voltage_V, 20.0)) << k;
  }
  EXPECT_EQ(agent::seeded_noise(7, 1, 3), agent::seeded_noise(7, 1, 3));
  EXPECT_NE(agent::seeded_noise(7, 1, 3), agent::seeded_noise(8, 1, 3));
}

}  // namespace
