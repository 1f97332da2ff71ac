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

std::string csv_header(const std::vector<std::string>& columns) {
  std::string header;
  for (size_t c = 0; c < columns.size(); ++c) header += (c ? "," : "") + columns[c];
  return header;
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out;
  size_t start = 0;
  for (size_t comma; (comma = line.find(',', start)) != std::string::npos; start = comma + 1)
    out.push_back(line.substr(start, comma - start));
  out.push_back(line.substr(start));
  return out;
}

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& columns, bool active, bool append)
    : path_(path), ncols_(columns.size()) {
  if (!active) return;
  file_ = std::fopen(path.c_str(), append ? "a" : "w");
  if (!file_) throw std::runtime_error("cannot write '" + path + "': check that the output directory is writable");
  if (!append) {
    std::fprintf(file_, "%s\n", csv_header(columns).c_str());
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
