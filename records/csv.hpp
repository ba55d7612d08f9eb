#pragma once
// Comma-separated records with a header line: the shared part of every CSV format in records/.
// A record's columns are described once, as a table of (name, unit, printf format); writers
// format a row through that table and readers look columns up by name in the file's header.
#include <cstddef>
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

}  // namespace maptr::records
