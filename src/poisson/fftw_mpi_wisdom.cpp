// FFTW wisdom beside a checkpoint (poisson/fft_wisdom.hpp); FFTW-MPI builds only.
#include <fftw3-mpi.h>

#include <filesystem>
#include <fstream>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "poisson/fft_wisdom.hpp"
#include "poisson/fftw_mpi_r2r.hpp"

namespace eulerfsi {

namespace {

constexpr const char* kTag = "eulerfsi-fftw-wisdom";
constexpr int kFormat = 1;

// This process's wisdom as FFTW's text.
std::string exported_wisdom() {
  char* text = fftw_export_wisdom_to_string();
  std::string out = text ? text : "";
  fftw_free(text);
  return out;
}

// Every rank's text on rank 0, in rank order (nothing elsewhere).
std::vector<std::string> gather_on_root(const std::string& mine, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  int length = int(mine.size());
  std::vector<int> lengths(size_t(size), 0), offsets(size_t(size), 0);
  MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, comm);
  std::partial_sum(lengths.begin(), lengths.end() - 1, offsets.begin() + 1);
  std::string all(rank == 0 ? size_t(offsets.back() + lengths.back()) : 0, '\0');
  MPI_Gatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0, comm);
  std::vector<std::string> texts;
  if (rank == 0)
    for (int r = 0; r < size; ++r) texts.push_back(all.substr(size_t(offsets[size_t(r)]), size_t(lengths[size_t(r)])));
  return texts;
}

// Rank r receives rank 0's texts[r].
std::string scatter_from_root(const std::vector<std::string>& texts, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  std::vector<int> lengths(size_t(size), 0), offsets(size_t(size), 0);
  std::string all;
  if (rank == 0)
    for (int r = 0; r < size; ++r) lengths[size_t(r)] = int(texts[size_t(r)].size()), all += texts[size_t(r)];
  std::partial_sum(lengths.begin(), lengths.end() - 1, offsets.begin() + 1);
  int length = 0;
  MPI_Scatter(lengths.data(), 1, MPI_INT, &length, 1, MPI_INT, 0, comm);
  std::string mine(size_t(length), '\0');
  MPI_Scatterv(all.data(), lengths.data(), offsets.data(), MPI_CHAR, mine.data(), length, MPI_CHAR, 0, comm);
  return mine;
}

// Rank 0's text on every rank.
std::string broadcast(std::string text, MPI_Comm comm) {
  int length = int(text.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, comm);
  text.resize(size_t(length));
  MPI_Bcast(text.data(), length, MPI_CHAR, 0, comm);
  return text;
}

// Writes the file under a temporary name and renames it: a crash never leaves half a file.
std::string write_wisdom_file(const std::string& path, const std::vector<std::string>& texts) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << kTag << ' ' << kFormat << " ranks " << texts.size() << '\n';
    for (size_t r = 0; r < texts.size(); ++r) out << "rank " << r << " bytes " << texts[r].size() << '\n' << texts[r];
    out.close();
    if (!out) return "cannot write the FFTW wisdom '" + tmp + "' (permissions or disk full?)";
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  return ec ? "cannot rename '" + tmp + "' to '" + path + "': " + ec.message() : "";
}

// Each rank's text from the file into `texts`, or why the file cannot be used.
std::string read_wisdom_file(const std::string& path, std::vector<std::string>& texts) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "no FFTW wisdom file '" + path + "'";
  const std::string damaged = "the FFTW wisdom file '" + path + "' is damaged";
  std::string tag, word;
  int format = 0, ranks = 0;
  in >> tag >> format >> word >> ranks;
  if (!in || tag != kTag || format != kFormat || word != "ranks" || ranks < 1) return damaged;
  for (int r = 0; r < ranks; ++r) {
    std::string rank_word, bytes_word;
    int index = -1;
    long bytes = -1;
    in >> rank_word >> index >> bytes_word >> bytes;
    if (!in || rank_word != "rank" || index != r || bytes_word != "bytes" || bytes < 0 || in.get() != '\n') return damaged;
    std::string text(size_t(bytes), '\0');
    if (!in.read(text.data(), bytes)) return damaged;
    texts.push_back(std::move(text));
  }
  return "";
}

}  // namespace

void save_fft_wisdom(const std::string& path, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::vector<std::string> texts = gather_on_root(exported_wisdom(), comm);
  // every rank throws together, or the others would wait in the next collective
  const std::string error = broadcast(rank == 0 ? write_wisdom_file(path, texts) : "", comm);
  if (!error.empty()) throw std::runtime_error(error);
}

bool load_fft_wisdom(const std::string& path, MPI_Comm comm, std::string* why) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  std::vector<std::string> texts;
  std::string problem;
  if (rank == 0) {
    problem = read_wisdom_file(path, texts);
    if (problem.empty() && int(texts.size()) != size)
      problem = "the FFTW wisdom '" + path + "' was written by " + std::to_string(texts.size()) + " ranks, this run has " +
                std::to_string(size);
  }
  problem = broadcast(problem, comm);
  ensure_fftw_mpi_init();
  const std::string mine = problem.empty() ? scatter_from_root(texts, comm) : "";
  // the stored wisdom and nothing else: what this process planned before must not mix in
  fftw_forget_wisdom();
  int imported = problem.empty() ? fftw_import_wisdom_from_string(mine.c_str()) : 1, everywhere = 0;
  MPI_Allreduce(&imported, &everywhere, 1, MPI_INT, MPI_MIN, comm);
  if (!everywhere) {
    fftw_forget_wisdom();
    problem = "FFTW refused the wisdom in '" + path + "'";
  }
  if (why) *why = problem;
  return problem.empty();
}

}  // namespace eulerfsi
