#include "records/result_table.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "records/csv.hpp"

namespace maptr::records {

using nlohmann::json;

namespace {
/// Default decimals of a number in a column without its own.
constexpr int kDefaultDecimals = 6;

/// A CSV field back to text: the quotes csv_field() added removed.
std::string unquote(const std::string& f) {
  if (f.size() < 2 || f.front() != '"' || f.back() != '"') return f;
  std::string s;
  for (std::size_t i = 1; i + 1 < f.size(); ++i) {
    s += f[i];
    if (f[i] == '"' && f[i + 1] == '"') ++i;
  }
  return s;
}
}  // namespace

std::string fixed(double v, int prec) {
  if (!std::isfinite(v)) return "";
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", prec, v);
  return buf;
}

json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

std::string csv_field(const json& v, int prec) {
  if (v.is_null()) return "";
  if (v.is_string()) {
    std::string s = v.get<std::string>();
    if (s.find_first_of(",\"") == std::string::npos) return s;
    std::string q = "\"";
    for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return q + "\"";
  }
  if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number()) return fixed(v.get<double>(), prec >= 0 ? prec : kDefaultDecimals);
  return v.dump();
}

std::string ResultTable::csv_header() const {
  std::string o;
  for (const auto& c : cols)
    if (c.csv) o += (o.empty() ? "" : ",") + c.key;
  return o + "\n";
}

std::string ResultTable::csv_row(const json& r) const {
  std::string o;
  bool first = true;
  for (const auto& c : cols) {
    if (!c.csv) continue;
    o += (first ? "" : ",") + csv_field(r.contains(c.key) ? r[c.key] : json(nullptr), c.prec);
    first = false;
  }
  return o + "\n";
}

std::string ResultTable::csv() const {
  std::string o = csv_header();
  for (const auto& r : rows) o += csv_row(r);
  return o;
}

std::string ResultTable::md() const {
  std::ostringstream o;
  o << "|";
  for (const auto& c : cols)
    if (c.md) o << " " << c.head << " |";
  o << "\n|";
  for (const auto& c : cols)
    if (c.md) o << "---|";
  o << "\n";
  for (const auto& r : rows) {
    o << "|";
    for (const auto& c : cols) {
      if (!c.md) continue;
      const json v = r.contains(c.key) ? r[c.key] : json(nullptr);
      const std::string s = v.is_null() ? "–" : v.is_string() ? v.get<std::string>() : csv_field(v, c.prec);
      o << " " << s << " |";
    }
    o << "\n";
  }
  return o.str();
}

std::vector<json> read_result_table(const std::string& path, const std::vector<ResultColumn>& cols) {
  const auto f = CsvFile::read(path, path.substr(path.find_last_of('/') + 1));
  std::vector<json> rows(f.rows(), json::object());
  for (const auto& c : cols) {
    if (!c.csv) continue;
    const std::size_t at = f.column(c.key);
    for (std::size_t i = 0; i < f.rows(); ++i) {
      const std::string& s = f.text(i, at);
      rows[i][c.key] = s.empty() ? json(nullptr) : c.prec < 0 ? json(unquote(s)) : json(f.number(i, at));
    }
  }
  return rows;
}

void ResultTable::write_csv(const std::string& path) const { write_text_file(path, csv()); }

ResultTableWriter::ResultTableWriter(const std::string& path, std::vector<ResultColumn> cols) : out_(path) {
  layout_.cols = std::move(cols);
  out_ << layout_.csv_header() << std::flush;
}

void ResultTableWriter::append(const json& row) { out_ << layout_.csv_row(row) << std::flush; }

void write_text_file(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
  f.flush();
  if (!f) throw RecordError(path + ": cannot be written");
}

}  // namespace maptr::records
