#pragma once
// The result tables of `maptr experiment` and `maptr bench`: one set of rows (JSON objects keyed
// by column) written as CSV (keys as the header), as a markdown table (human headers) and read
// back from the CSV.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace maptr::deploy::report {

/// `v` with `prec` decimals; "" when it is not finite.
std::string fixed(double v, int prec);

/// A finite number as JSON, null otherwise (NaN marks a value a run did not produce).
nlohmann::json num(double v);

/// One column of a table.
struct Column {
  std::string key, head;
  int prec = 2;     ///< decimals; -1 for text
  bool md = true;   ///< shown in the markdown table
  bool csv = true;  ///< written to the CSV
};

/// One value as a CSV field: numbers with the column's decimals, booleans as 1/0, text quoted
/// when it holds a comma or a quote, null as "".
std::string csv_field(const nlohmann::json& v, int prec);

struct Table {
  std::vector<Column> cols;
  std::vector<nlohmann::json> rows;

  std::string csv_header() const;
  std::string csv_row(const nlohmann::json& row) const;
  std::string csv() const;
  /// The markdown table: the `md` columns, "–" for a missing value.
  std::string md() const;
};

/// Reads a CSV written by Table::csv() back into rows: text columns (prec -1) as strings,
/// the others as numbers, empty fields as null. Columns are found by key; throws
/// records::RecordError when one is missing or a number is malformed.
std::vector<nlohmann::json> read_table_csv(const std::string& path, const std::vector<Column>& cols);

/// Writes `text` to `path`.
void write_file(const std::string& path, const std::string& text);

}  // namespace maptr::deploy::report
