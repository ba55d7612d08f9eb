#pragma once
// The paper's Table "Straight-line power saving for a 16 agent system" (Type-I motors, straight
// line, 30 min, ~36 km): its own numbers, the only values of the experiments not produced by a
// run.
#include <cmath>

namespace maptr::deploy::paper {

struct PowerRow {
  double gross_kg;
  double e_no_kJ, e_ec_kJ;        ///< energy drawn, every agent (NO) and energy-conscious (EC)
  double saving_pct;              ///< (E_NO - E_EC) / E_NO
  double active;                  ///< active agents chosen by EC (L + R)
  double mileage_no, mileage_ec;  ///< m/J
};

inline constexpr PowerRow kPowerTable[] = {
    {13.2, 92.33, 63.17, 31.58, 3, 0.4098, 0.5347},   {18.2, 111.69, 87.46, 21.70, 5, 0.3359, 0.3970},
    {23.2, 131.05, 108.94, 16.87, 6, 0.2838, 0.3171}, {28.2, 150.41, 132.81, 11.7, 8, 0.2452, 0.2633},
    {33.2, 169.77, 156.58, 7.77, 10, 0.2153, 0.2249}, {38.2, 189.13, 180.35, 4.64, 12, 0.1916, 0.1962}};

/// The paper's row at this gross mass, or nullptr.
inline const PowerRow* power_row(double gross_kg) {
  constexpr double kMassTolerance = 1e-6;
  for (const auto& r : kPowerTable)
    if (std::fabs(r.gross_kg - gross_kg) < kMassTolerance) return &r;
  return nullptr;
}

/// The battery experiment: EC lasted about this much longer than NO (6395 mAh, 30 kg payload).
inline constexpr double kBatteryEcLongerS = 800.0;

}  // namespace maptr::deploy::paper
