#pragma once
// A CSV time series written by rank 0 only, one flushed row at a time so a crash loses at most
// the row being written.
#include <cstdio>
#include <string>
#include <vector>

namespace eulerfsi {

class CsvWriter {
 public:
  CsvWriter() = default;
  // append = true continues an existing file (restart) instead of truncating it.
  CsvWriter(const std::string& path, const std::vector<std::string>& columns, bool active, bool append = false);
  ~CsvWriter();
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;
  CsvWriter(CsvWriter&& o) noexcept;
  CsvWriter& operator=(CsvWriter&& o) noexcept;

  void row(const std::vector<double>& values);
  const std::string& path() const { return path_; }

 private:
  std::FILE* file_ = nullptr;
  std::string path_;
  size_t ncols_ = 0;
};

// Formats a double the way every CSV of ours does: 17 significant digits, so rows round-trip.
std::string format_number(double v);

// The header line of `columns` (comma-joined), and a line split at its commas (no quoting: our
// CSVs hold names and numbers only).
std::string csv_header(const std::vector<std::string>& columns);
std::vector<std::string> split_csv_line(const std::string& line);

}  // namespace eulerfsi
