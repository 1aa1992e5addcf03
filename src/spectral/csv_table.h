// A plain CSV table as Rimu's data files use them: one header line, comma-separated cells, '#' comments.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace rimu {

/// A CSV file read into memory, with the source line of every row kept so that later validation
/// (a non-numeric cell, a non-monotonic wavelength) can name the exact line.
class CsvTable {
 public:
  /// Reads `path`. Throws InputError if the file is missing, empty, or a row has the wrong cell count.
  static CsvTable read(const std::filesystem::path& path);
  /// Parses CSV text already in memory; `name` is used in error messages.
  static CsvTable parse(std::string_view text, const std::string& name);

  const std::string& name() const { return name_; }
  const std::vector<std::string>& header() const { return header_; }
  size_t row_count() const { return rows_.size(); }
  size_t column_count() const { return header_.size(); }
  const std::string& cell(size_t row, size_t column) const { return rows_[row][column]; }
  /// 1-based line in the file of data row `row`.
  int line_of_row(size_t row) const { return lines_[row]; }

  /// Index of the column called `column_name`; throws InputError naming the columns that exist.
  size_t column_index(std::string_view column_name) const;
  /// Every cell of a column as a finite number; throws InputError with file:line on the first bad cell.
  std::vector<double> numbers(size_t column) const;

 private:
  std::string name_;
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
  std::vector<int> lines_;
};

/// Parses one cell as a finite double (no trailing garbage); false if it is not one.
bool parse_finite_number(std::string_view text, double& value);

}  // namespace rimu
