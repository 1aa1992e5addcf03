#include "spectral/io/csv_table.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "spectral/error.h"
#include "spectral/io/input_file.h"

namespace rimu {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string> split_cells(std::string_view line) {
  std::vector<std::string> cells;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    cells.emplace_back(trim(line.substr(start, comma == std::string_view::npos ? line.npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return cells;
}

}  // namespace

bool parse_finite_number(std::string_view text, double& value) {
  text = trim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return false;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size() && std::isfinite(value);
}

CsvTable CsvTable::read(const std::filesystem::path& path) {
  return parse(read_input_file(path, kMaxTableFileBytes), path.string());
}

CsvTable CsvTable::parse(std::string_view text, const std::string& name) {
  reject_nul_bytes(text, name);
  CsvTable table;
  table.name_ = name;
  int line_number = 0;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t newline = text.find('\n', start);
    const std::string_view line =
        trim(text.substr(start, newline == std::string_view::npos ? text.npos : newline - start));
    ++line_number;
    start = newline == std::string_view::npos ? text.size() + 1 : newline + 1;
    if (line.empty() || line.front() == '#') continue;
    // Another separator than the comma would make every line one cell, or split "0,5" decimals wrongly.
    const bool semicolons = line.find(';') != std::string_view::npos;
    if (semicolons || (line.find(',') == std::string_view::npos && line.find('\t') != std::string_view::npos))
      throw InputError({name, line_number, ""}, std::string("cells are separated by ") +
                                                    (semicolons ? "semicolons" : "tabs") + "; expected " +
                                                    kExpectedCsvLayout);
    std::vector<std::string> cells = split_cells(line);
    if (table.header_.empty() && !table.headerless_) {
      // A first line of numbers is data: a table written without a header keeps its first row, and its columns
      // get the names a spectrum table's columns have.
      const bool numeric = std::all_of(cells.begin(), cells.end(), [](const std::string& c) {
        double unused = 0.0;
        return parse_finite_number(c, unused);
      });
      if (!numeric) {
        table.header_ = std::move(cells);
        continue;
      }
      table.headerless_ = true;
      table.header_.push_back("wavelength_nm");
      for (size_t c = 1; c < cells.size(); ++c)
        table.header_.push_back(cells.size() == 2 ? "value" : "column_" + std::to_string(c + 1));
    }
    if (cells.size() != table.header_.size()) {
      throw InputError({name, line_number, ""}, "expected " + std::to_string(table.header_.size()) +
                                                     " comma-separated cells (as in the " +
                                                     (table.headerless_ ? "first row" : "header") + "), found " +
                                                     std::to_string(cells.size()));
    }
    table.rows_.push_back(std::move(cells));
    table.lines_.push_back(line_number);
  }
  if (table.header_.empty())
    throw InputError({name, 0, ""}, std::string("the file is empty: expected ") + kExpectedCsvLayout);
  if (table.rows_.empty()) throw InputError({name, 0, ""}, "the file has a header but no data rows");
  return table;
}

size_t CsvTable::column_index(std::string_view column_name) const {
  for (size_t i = 0; i < header_.size(); ++i)
    if (header_[i] == column_name) return i;
  std::string known;
  for (const auto& h : header_) known += (known.empty() ? "" : ", ") + h;
  throw InputError({name_, headerless_ ? 0 : 1, ""},
                   "no column '" + std::string(column_name) + "'; the columns are: " + known +
                       (headerless_ ? " (the file has no header line, so its columns have these default names)" : ""));
}

std::vector<double> CsvTable::numbers(size_t column) const {
  std::vector<double> values(rows_.size());
  for (size_t r = 0; r < rows_.size(); ++r) {
    if (!parse_finite_number(rows_[r][column], values[r])) {
      // from_chars refuses what a double cannot hold (1e-400, 1e400, most subnormals): say so, not "not a number".
      double unused = 0.0;
      const std::string& text = rows_[r][column];
      const char* begin = text.data() + (text.starts_with('+') ? 1 : 0);
      if (std::from_chars(begin, text.data() + text.size(), unused).ec == std::errc::result_out_of_range)
        throw InputError({name_, lines_[r], ""}, "column '" + header_[column] + "': " + text +
                                                      " is beyond the range of double-precision numbers (magnitudes "
                                                      "2.2e-308 to 1.8e308); spectral values must be 0 or 1e-30 to "
                                                      "1e30");
      throw InputError({name_, lines_[r], ""}, "column '" + header_[column] + "': expected a finite number, found '" +
                                                    rows_[r][column] + "'");
    }
  }
  return values;
}

}  // namespace rimu
