#pragma once
// CsvWriter: one CSV time series (RFC 4180). Header of column names, then rows of numbers or text.
// Numbers are written so they read back exactly (FormatDouble). The file appears under its final
// name only on Close() (or normal destruction); see AtomicFile.
//
//   CsvWriter csv(out.Path("errors.csv"), {"t_s", "position_error_m", "status"});
//   csv.WriteRow({0.01, 0.25});                        // numbers only
//   csv.WriteCells({CsvCell(0.02), CsvCell(0.24), CsvCell("tracking")});
//   csv.Close();
#include <string>
#include <variant>
#include <vector>

#include "output/atomic_file.h"

namespace aperture::output {

using CsvCell = std::variant<double, std::string>;

class CsvWriter {
 public:
  // std::invalid_argument when `columns` is empty; std::runtime_error when `path` cannot be
  // written.
  CsvWriter(const std::string& path, const std::vector<std::string>& columns);

  // Each row must have exactly one value per column (std::invalid_argument naming the file).
  void WriteRow(const std::vector<double>& values);
  void WriteCells(const std::vector<CsvCell>& cells);

  void Close() { file_.Commit(); }
  std::size_t rows_written() const { return rows_written_; }
  const std::string& path() const { return file_.path(); }

 private:
  void CheckWidth(std::size_t width) const;
  void WriteCell(const std::string& text);

  AtomicFile file_;
  std::size_t column_count_;
  std::size_t rows_written_ = 0;
};

// Quotes `text` when it contains a comma, quote, CR or LF (RFC 4180).
std::string EscapeCsvField(const std::string& text);

}  // namespace aperture::output
