// A plain CSV table as Rimu's data files use them: one header line, comma-separated cells, '#' comments.
// A file whose first line is all numbers has no header: that line is data, and the columns are called
// wavelength_nm, value (two columns) or wavelength_nm, column_2, column_3, ...
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace rimu {

/// A CSV file read into memory, with the source line of every row kept so that later validation
/// (a non-numeric cell, a non-monotonic wavelength) can name the exact line.
/// What a spectrum table looks like, for messages about files that are not one.
inline constexpr const char* kExpectedCsvLayout =
    "a header line such as 'wavelength_nm,value', then one 'wavelength,value' row per line, with wavelengths in "
    "nanometres and cells separated by commas (decimal point '.')";

class CsvTable {
 public:
  /// Reads `path` (a regular file of at most kMaxTableFileBytes, input_file.h). Throws InputError if the file is
  /// missing, not a regular file, empty, holds a NUL byte, uses ';' or tabs as separators, or a row has the wrong
  /// cell count.
  static CsvTable read(const std::filesystem::path& path);
  /// Parses CSV text already in memory; `name` is used in error messages.
  static CsvTable parse(std::string_view text, const std::string& name);

  const std::string& name() const { return name_; }
  const std::vector<std::string>& header() const { return header_; }
  /// True if the first line was data (then header() holds the default names).
  bool headerless() const { return headerless_; }
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
  bool headerless_ = false;
};

/// Parses one cell as a finite double (no trailing garbage); false if it is not one.
bool parse_finite_number(std::string_view text, double& value);

}  // namespace rimu
