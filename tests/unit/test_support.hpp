#pragma once
// Helpers shared by the unit tests: recording measured errors in the gtest XML, and an
// independent scalar root finder for closed-form comparisons.
#include <gtest/gtest.h>

#include <functional>
#include <iomanip>
#include <sstream>
#include <string>

namespace maptr::test {

/// Records a measured value (e.g. an error against a closed form) as a test property.
inline void record(const std::string& key, double value) {
  std::ostringstream os;
  os << std::setprecision(3) << std::scientific << value;
  ::testing::Test::RecordProperty(key, os.str());
}

/// Root of f on [lo, hi] by bisection (f(lo), f(hi) of opposite signs), to |hi - lo| < tol.
inline double bisect(const std::function<double(double)>& f, double lo, double hi, double tol) {
  double flo = f(lo);
  EXPECT_LT(flo * f(hi), 0.0) << "no sign change on [" << lo << ", " << hi << "]";
  while (hi - lo > tol) {
    const double mid = 0.5 * (lo + hi);
    const double fm = f(mid);
    if ((fm < 0.0) == (flo < 0.0)) {
      lo = mid;
      flo = fm;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

}  // namespace maptr::test
