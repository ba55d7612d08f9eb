#pragma once
// Comma-separated records with a header line: the shared part of every CSV format in records/.
// A record's columns are described once, as a table of (name, unit, printf format); writers
// format a row through that table and readers look columns up by name in the file's header.
#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace maptr::records {

/// A file does not hold what its format says: a missing column, a malformed number, no header.
class RecordError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One column of a record: its name in the header, its unit ("" when it has none) and the printf
/// format of one value (numbers are passed as double; integer columns use "%.0f").
struct ColumnSpec {
  const char* name;
  const char* unit;
  const char* format;
};

/// The header line (names joined by commas, with the newline).
std::string header_line(const std::vector<ColumnSpec>& cols);

/// One value in a column's format.
std::string format_value(const ColumnSpec& col, double v);

/// A CSV file written one flushed line at a time (a killed writer leaves whole lines). kNew
/// starts the file with its header; kAppend continues what is there (a restarted process
/// continues its file) and writes the header only when the file is new or empty.
class CsvLines {
 public:
  enum class Mode { kNew, kAppend };
  /// Throws RecordError when `path` cannot be opened.
  CsvLines(const std::string& path, const std::string& header, Mode mode);
  ~CsvLines();
  CsvLines(const CsvLines&) = delete;
  CsvLines& operator=(const CsvLines&) = delete;
  void write(const std::string& line);

 private:
  std::FILE* f_ = nullptr;
};

/// Appends the rows of the CSV text `text` (its header line left out) to the CSV file `path`,
/// which has the same columns: one file continued by another writer (a process restarted
/// elsewhere).
void append_csv_rows(const std::string& path, const std::string& text);

/// A CsvLines of records of type Row, each line made by `Format`.
template <class Row, std::string (*Format)(const Row&)>
class RowWriter {
 public:
  RowWriter(const std::string& path, const std::string& header, CsvLines::Mode mode)
      : lines_(path, header, mode) {}
  void write(const Row& r) { lines_.write(Format(r)); }

 private:
  CsvLines lines_;
};

/// Splits one CSV line at the commas outside double quotes (quotes are kept in the fields).
std::vector<std::string> split_fields(const std::string& line);

/// A CSV file read as text, with its header; columns are found by name.
class CsvFile {
 public:
  /// Reads `path`; `what` names the file in errors (e.g. "trace.csv"). An empty file has no
  /// header and no rows. A last line without its newline (a writer killed mid-line) is not
  /// read. Throws RecordError when the file cannot be opened.
  static CsvFile read(const std::string& path, const std::string& what);
  /// Parses text (the file's whole content).
  static CsvFile parse(const std::string& text, const std::string& what);

  /// Index of a column; throws RecordError naming the column and the file when it is missing.
  std::size_t column(const std::string& name) const;
  bool has_column(const std::string& name) const;
  std::size_t rows() const { return rows_.size(); }
  /// The text of a cell ("" past the end of a short row).
  const std::string& text(std::size_t row, std::size_t col) const;
  /// A cell as a number; throws RecordError (file, line, column, text) when it is not one.
  double number(std::size_t row, std::size_t col) const;
  const std::vector<std::string>& header() const { return header_; }

 private:
  std::string what_;
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

/// The rows of a file whose columns are all numbers: `cols` is the format's table (entries with
/// a `spec`), `set(row, column, value)` stores one value. Throws RecordError naming a missing
/// column or a malformed number.
template <class Row, class Column, class Set>
std::vector<Row> numeric_rows(const CsvFile& f, const std::vector<Column>& cols, Set set) {
  std::vector<std::size_t> at;
  for (const auto& c : cols) at.push_back(f.column(c.spec.name));
  std::vector<Row> out(f.rows());
  for (std::size_t i = 0; i < f.rows(); ++i)
    for (std::size_t k = 0; k < cols.size(); ++k) set(out[i], cols[k], f.number(i, at[k]));
  return out;
}

}  // namespace maptr::records
