#include "output/csv_writer.h"

#include <stdexcept>

#include "output/number_format.h"

namespace aperture::output {

std::string EscapeCsvField(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) {
    quoted += c;
    if (c == '"') quoted += '"';
  }
  return quoted + "\"";
}

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& columns)
    : file_(path), column_count_(columns.size()) {
  if (columns.empty()) {
    file_.Discard();
    throw std::invalid_argument("CsvWriter for '" + path + "' needs at least one column name");
  }
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (i > 0) file_.stream() << ',';
    file_.stream() << EscapeCsvField(columns[i]);
  }
  file_.stream() << '\n';
}

void CsvWriter::CheckWidth(std::size_t width) const {
  if (width != column_count_) {
    throw std::invalid_argument("CSV row " + std::to_string(rows_written_ + 1) + " of '" + path() +
                                "' has " + std::to_string(width) + " values, expected " +
                                std::to_string(column_count_) + " (one per column)");
  }
}

void CsvWriter::WriteRow(const std::vector<double>& values) {
  CheckWidth(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i > 0) file_.stream() << ',';
    file_.stream() << FormatDouble(values[i]);
  }
  file_.stream() << '\n';
  ++rows_written_;
}

void CsvWriter::WriteCells(const std::vector<CsvCell>& cells) {
  CheckWidth(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i > 0) file_.stream() << ',';
    if (const double* number = std::get_if<double>(&cells[i])) {
      file_.stream() << FormatDouble(*number);
    } else {
      file_.stream() << EscapeCsvField(std::get<std::string>(cells[i]));
    }
  }
  file_.stream() << '\n';
  ++rows_written_;
}

}  // namespace aperture::output
