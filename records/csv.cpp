#include "records/csv.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace maptr::records {

std::string header_line(const std::vector<ColumnSpec>& cols) {
  std::string out;
  for (std::size_t i = 0; i < cols.size(); ++i) out += (i ? "," : "") + std::string(cols[i].name);
  return out + "\n";
}

CsvLines::CsvLines(const std::string& path, const std::string& header, Mode mode)
    : f_(std::fopen(path.c_str(), mode == Mode::kNew ? "w" : "a")) {
  if (!f_) throw RecordError("cannot write " + path);
  if (std::ftell(f_) == 0) write(header);
}

CsvLines::~CsvLines() { std::fclose(f_); }

void CsvLines::write(const std::string& line) {
  std::fputs(line.c_str(), f_);
  std::fflush(f_);
}

void append_csv_rows(const std::string& path, const std::string& text) {
  const auto eol = text.find('\n');
  if (eol == std::string::npos) return;
  std::FILE* f = std::fopen(path.c_str(), "ab");
  if (!f) throw RecordError("cannot write " + path);
  std::fwrite(text.data() + eol + 1, 1, text.size() - eol - 1, f);
  std::fclose(f);
}

std::string format_value(const ColumnSpec& col, double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), col.format, v);
  return buf;
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  bool quoted = false;  // a comma inside "..." belongs to the field
  for (std::size_t i = 0; i <= line.size(); ++i) {
    if (i < line.size() && line[i] == '"') quoted = !quoted;
    if (i == line.size() || (line[i] == ',' && !quoted)) {
      out.push_back(line.substr(start, i - start));
      start = i + 1;
    }
  }
  return out;
}

CsvFile CsvFile::read(const std::string& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw RecordError(what + ": cannot read " + path);
  std::stringstream ss;
  ss << in.rdbuf();
  return parse(ss.str(), what);
}

CsvFile CsvFile::parse(const std::string& text, const std::string& what) {
  CsvFile f;
  f.what_ = what;
  std::stringstream in(text);
  std::string line;
  if (!std::getline(in, line)) return f;
  f.header_ = split_fields(line);
  while (std::getline(in, line)) {
    if (in.eof()) break;  // no newline after it: a write that was interrupted
    if (!line.empty()) f.rows_.push_back(split_fields(line));
  }
  return f;
}

bool CsvFile::has_column(const std::string& name) const {
  for (const auto& h : header_)
    if (h == name) return true;
  return false;
}

std::size_t CsvFile::column(const std::string& name) const {
  for (std::size_t i = 0; i < header_.size(); ++i)
    if (header_[i] == name) return i;
  throw RecordError(what_ + ": no column '" + name + "' in the header");
}

const std::string& CsvFile::text(std::size_t row, std::size_t col) const {
  static const std::string empty;
  const auto& r = rows_.at(row);
  return col < r.size() ? r[col] : empty;
}

double CsvFile::number(std::size_t row, std::size_t col) const {
  const std::string& s = text(row, col);
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size())
    throw RecordError(what_ + " line " + std::to_string(row + 2) + ", column '" +
                      (col < header_.size() ? header_[col] : std::to_string(col)) + "': '" + s +
                      "' is not a number");
  return v;
}

}  // namespace maptr::records
