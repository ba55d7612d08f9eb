#pragma once
// The result tables of the studies (`maptr experiment`, `maptr bench`) and their series: one set
// of rows (JSON objects keyed by column) written as CSV (keys as the header), as a markdown table
// (human headers) and read back from the CSV. Each table's columns are in
// records/study_columns.hpp; the files' layout, number formats and writing live here.
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace maptr::records {

/// `v` with `prec` decimals; "" when it is not finite.
std::string fixed(double v, int prec);

/// A finite number as JSON, null otherwise (NaN marks a value a run did not produce).
nlohmann::json num(double v);

/// One column of a table.
struct ResultColumn {
  std::string key, head;
  int prec = 2;     ///< decimals; -1 for text
  bool md = true;   ///< shown in the markdown table
  bool csv = true;  ///< written to the CSV
};

/// One value as a CSV field: numbers with the column's decimals, booleans as 1/0, text quoted
/// when it holds a comma or a quote, null as "".
std::string csv_field(const nlohmann::json& v, int prec);

struct ResultTable {
  std::vector<ResultColumn> cols;
  std::vector<nlohmann::json> rows;

  std::string csv_header() const;
  std::string csv_row(const nlohmann::json& row) const;
  std::string csv() const;
  /// The markdown table: the `md` columns, "–" for a missing value.
  std::string md() const;
  /// Writes csv() to `path`.
  void write_csv(const std::string& path) const;
};

/// A result table's CSV written a row at a time, each row flushed as it comes: a study that
/// fails at a later size leaves the rows before it.
class ResultTableWriter {
 public:
  /// Creates `path` with the header of `cols`' CSV columns.
  ResultTableWriter(const std::string& path, std::vector<ResultColumn> cols);
  /// Appends one row (a column it lacks is written empty).
  void append(const nlohmann::json& row);

 private:
  ResultTable layout_;
  std::ofstream out_;
};

/// Reads a CSV written by ResultTable::csv() back into rows: text columns (prec -1) as strings,
/// the others as numbers, empty fields as null. Columns are found by key; throws
/// records::RecordError when one is missing or a number is malformed.
std::vector<nlohmann::json> read_result_table(const std::string& path, const std::vector<ResultColumn>& cols);

/// Writes `text` to `path` (a markdown table, a plot script, a JUnit file); throws RecordError
/// when it cannot be written.
void write_text_file(const std::string& path, const std::string& text);

}  // namespace maptr::records
