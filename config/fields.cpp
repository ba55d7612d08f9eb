#include "config/fields.hpp"

#include <cmath>
#include <sstream>

#include "model/motor.hpp"

namespace maptr::config {

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  if (min_open ? !(v > min) : !(v >= min)) return false;
  if (max_open ? !(v < max) : !(v <= max)) return false;
  if (nonzero && v == 0.0) return false;
  return multiple_of <= 1 || std::fmod(v, static_cast<double>(multiple_of)) == 0.0;
}

std::string Range::describe() const {
  return (min_open ? "(" : "[") + model::param_value(min) + ", " + model::param_value(max) +
         (max_open ? ")" : "]");
}

namespace detail {

// ---- Value formatting ----

/// A value as to_yaml() writes it: doubles with 17 significant digits (they read back exact).
std::string yaml_scalar(const Value& v) {
  if (const double* d = std::get_if<double>(&v)) {
    if (std::isnan(*d)) return ".nan";
    if (std::isinf(*d)) return *d > 0 ? ".inf" : "-.inf";
    std::ostringstream os;
    os.precision(17);
    os << *d;
    return os.str();
  }
  if (const long long* i = std::get_if<long long>(&v)) return std::to_string(*i);
  if (const bool* b = std::get_if<bool>(&v)) return *b ? "true" : "false";
  return std::get<std::string>(v);
}

/// A value as error messages print it (numbers with 6 significant digits).
std::string message_value(const Value& v) {
  if (const double* d = std::get_if<double>(&v)) return model::param_value(*d);
  return yaml_scalar(v);
}

/// At most kMaxQuotedChars bytes of `text` (cut on a UTF-8 boundary, then "…"), control
/// characters shown as '?', so that a message stays one short line.
std::string quoted(const std::string& text) {
  std::size_t n = std::min(text.size(), kMaxQuotedChars);
  if (n < text.size())
    while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80) --n;
  std::string out = text.substr(0, n);
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) c = '?';
  return n < text.size() ? out + "…" : out;
}

std::string describe(const YAML::Node& v) {
  if (!v) return "(missing)";
  switch (v.Type()) {
    case YAML::NodeType::Scalar:
      return v.Scalar();
    case YAML::NodeType::Sequence:
      return v.size() == 0 ? "[]" : "(a list of " + std::to_string(v.size()) + ")";
    case YAML::NodeType::Map:
      return v.size() == 0 ? "{}" : "(a mapping)";
    default:
      return "~";
  }
}

std::string join(const std::string& prefix, const std::string& key) {
  return prefix.empty() ? key : prefix + "." + key;
}

// ---- Range and checks ----

std::string unit_suffix(const FieldInfo& f) { return f.unit.empty() || f.unit == "1" ? "" : " " + f.unit; }

/// "" if v is allowed in f, else why not.
std::string problem(const FieldInfo& f, const Value& v, std::string (*accept)(const std::string&)) {
  if (f.type == FieldType::kReal || f.type == FieldType::kInteger) {
    const double x =
        f.type == FieldType::kReal ? std::get<double>(v) : static_cast<double>(std::get<long long>(v));
    const std::string in = f.range.describe() + unit_suffix(f);
    if (!std::isfinite(x)) return "must be a finite number in " + in;
    if (!f.range.contains(x)) {
      std::string why = "must be in " + in;
      if (f.range.nonzero) why += ", not zero";
      if (f.range.multiple_of > 1) why += ", a multiple of " + std::to_string(f.range.multiple_of);
      return why;
    }
    return "";
  }
  if (f.type != FieldType::kText) return "";
  const std::string& s = std::get<std::string>(v);
  if (std::find(f.choices.begin(), f.choices.end(), s) != f.choices.end()) return "";
  if (accept) return accept(s);
  std::string list;
  for (const auto& c : f.choices) list += (list.empty() ? "" : ", ") + c;
  return "must be one of " + list;
}

/// Converts a YAML value to the field's type, or fails naming the field.
Value convert(const FieldInfo& f, const YAML::Node& n, const std::string& field, const Context& c) {
  static const char* kTypeWords[] = {"a number", "an integer", "true or false", "a string"};
  const char* want = kTypeWords[static_cast<int>(f.type)];
  if (!n.IsScalar()) c.fail(field, describe(n), std::string("must be ") + want);
  try {
    switch (f.type) {
      case FieldType::kReal:
        return n.as<double>();
      case FieldType::kInteger:
        return n.as<long long>();
      case FieldType::kBool:
        return n.as<bool>();
      case FieldType::kText:
        return n.Scalar();
    }
  } catch (const std::exception&) {
  }
  c.fail(field, n.Scalar(), std::string("must be ") + want);
}

}  // namespace detail
}  // namespace maptr::config
