#include "io/csv_writer.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace eulerfsi {

std::string format_number(double v) {
  if (std::isnan(v)) return "nan";
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& columns, bool active, bool append)
    : path_(path), ncols_(columns.size()) {
  if (!active) return;
  file_ = std::fopen(path.c_str(), append ? "a" : "w");
  if (!file_) throw std::runtime_error("cannot write '" + path + "': check that the output directory is writable");
  if (!append) {
    std::string header;
    for (size_t c = 0; c < columns.size(); ++c) header += (c ? "," : "") + columns[c];
    std::fprintf(file_, "%s\n", header.c_str());
    std::fflush(file_);
  }
}

CsvWriter::~CsvWriter() {
  if (file_) std::fclose(file_);
}

CsvWriter::CsvWriter(CsvWriter&& o) noexcept
    : file_(std::exchange(o.file_, nullptr)), path_(std::move(o.path_)), ncols_(o.ncols_) {}

CsvWriter& CsvWriter::operator=(CsvWriter&& o) noexcept {
  if (this != &o) {
    if (file_) std::fclose(file_);
    file_ = std::exchange(o.file_, nullptr);
    path_ = std::move(o.path_);
    ncols_ = o.ncols_;
  }
  return *this;
}

void CsvWriter::row(const std::vector<double>& values) {
  if (!file_) return;
  std::string line;
  for (size_t c = 0; c < values.size(); ++c) line += (c ? "," : "") + format_number(values[c]);
  if (std::fprintf(file_, "%s\n", line.c_str()) < 0 || std::fflush(file_) != 0) {
    throw std::runtime_error("writing '" + path_ + "' failed (disk full?)");
  }
}

}  // namespace eulerfsi
