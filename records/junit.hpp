#pragma once
// JUnit XML, as CI systems read it: one <testsuite> of <testcase>s, each passed or with a
// <failure message="...">. Written by `maptr bench scale --junit FILE`.
#include <string>
#include <vector>

namespace maptr::records {

struct JunitCase {
  std::string name, classname;
  double time_s = 0;
  std::string failure;  ///< "" : passed
};

/// The whole file: the XML declaration, one <testsuite name=... tests=... failures=...
/// errors="0" skipped="0" time=...> holding the cases; text escaped for XML attributes.
std::string junit_xml(const std::string& suite, const std::vector<JunitCase>& cases);

}  // namespace maptr::records
