#include "records/junit.hpp"

#include <cstdio>
#include <sstream>

namespace maptr::records {

namespace {
std::string escaped(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      case '\n': out += "&#10;"; break;
      default:
        if (static_cast<unsigned char>(c) >= 0x20) out += c;  // other control characters are not XML
    }
  }
  return out;
}

std::string seconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.3f", s);
  return buf;
}
}  // namespace

std::string junit_xml(const std::string& suite, const std::vector<JunitCase>& cases) {
  int failures = 0;
  double total = 0;
  for (const auto& c : cases) {
    failures += !c.failure.empty();
    total += c.time_s;
  }
  std::ostringstream os;
  os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
     << "<testsuite name=\"" << escaped(suite) << "\" tests=\"" << cases.size() << "\" failures=\"" << failures
     << "\" errors=\"0\" skipped=\"0\" time=\"" << seconds(total) << "\">\n";
  for (const auto& c : cases) {
    os << "  <testcase name=\"" << escaped(c.name) << "\" classname=\"" << escaped(c.classname) << "\" time=\""
       << seconds(c.time_s) << "\"";
    if (c.failure.empty()) {
      os << "/>\n";
    } else {
      os << ">\n    <failure message=\"" << escaped(c.failure) << "\" type=\"threshold\">" << escaped(c.failure)
         << "</failure>\n  </testcase>\n";
    }
  }
  os << "</testsuite>\n";
  return os.str();
}

}  // namespace maptr::records
