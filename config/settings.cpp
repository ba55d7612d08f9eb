#include "config/settings.hpp"

#include <charconv>

namespace maptr::config {

std::string setting_value(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  return std::string(buf, r.ptr);
}
std::string setting_value(int v) { return std::to_string(v); }
std::string setting_value(bool v) { return v ? "true" : "false"; }
std::string setting_value(std::chrono::milliseconds v) { return std::to_string(v.count()); }

}  // namespace maptr::config
