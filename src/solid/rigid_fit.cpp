#include "solid/rigid_fit.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

namespace eulerfsi {

namespace {

// Solves the rows and columns `free` of A x = b (n x n, row-major) by Gaussian elimination with
// partial pivoting; the other unknowns are 0.
void solve_free(std::vector<double> a, std::vector<double> b, const std::vector<bool>& free, std::vector<double>& x) {
  const int n = int(b.size());
  std::vector<int> idx;
  for (int r = 0; r < n; ++r)
    if (free[r]) idx.push_back(r);
  const int m = int(idx.size());
  std::vector<double> A(m * m), B(m);
  for (int r = 0; r < m; ++r) {
    B[r] = b[idx[r]];
    for (int c = 0; c < m; ++c) A[r * m + c] = a[idx[r] * n + idx[c]];
  }
  for (int col = 0; col < m; ++col) {
    int piv = col;
    for (int r = col + 1; r < m; ++r)
      if (std::fabs(A[r * m + col]) > std::fabs(A[piv * m + col])) piv = r;
    if (!(std::fabs(A[piv * m + col]) > 0.0)) throw std::runtime_error("rigid body: its inertia is singular (no psi?)");
    for (int c = 0; c < m; ++c) std::swap(A[col * m + c], A[piv * m + c]);
    std::swap(B[col], B[piv]);
    for (int r = col + 1; r < m; ++r) {
      const double f = A[r * m + col] / A[col * m + col];
      for (int c = col; c < m; ++c) A[r * m + c] -= f * A[col * m + c];
      B[r] -= f * B[col];
    }
  }
  std::vector<double> y(m);
  for (int r = m - 1; r >= 0; --r) {
    double v = B[r];
    for (int c = r + 1; c < m; ++c) v -= A[r * m + c] * y[c];
    y[r] = v / A[r * m + r];
  }
  x.assign(n, 0.0);
  for (int r = 0; r < m; ++r) x[idx[r]] = y[r];
}

}  // namespace

RigidMotion fit_rigid_motion(const kernels::RigidMoments& m, const Comm& comm, const std::array<bool, 6>& held) {
  std::vector<double> a(36, 0.0), rhs(6, 0.0), x;
  const int ra[6] = {0, 1, 2, 0, 0, 1}, rb[6] = {0, 1, 2, 1, 2, 2};
  for (int d = 0; d < 3; ++d) {
    double first[3], q[3];
    for (int e = 0; e < 3; ++e) first[e] = comm.sum(m.first[d][e]);
    kernels::detail::lever(first, d, q);  // first_D x e_D
    a[d * 6 + d] = comm.sum(m.mass[d]);
    for (int e = 0; e < 3; ++e) a[d * 6 + 3 + e] = a[(3 + e) * 6 + d] = q[e];
    rhs[d] = comm.sum(m.momentum[d]);
    rhs[3 + d] = comm.sum(m.angular[d]);
  }
  for (int t = 0; t < kernels::kTensorComponents; ++t) {
    const double v = comm.sum(m.inertia[t]);
    a[(3 + ra[t]) * 6 + 3 + rb[t]] = a[(3 + rb[t]) * 6 + 3 + ra[t]] = v;
  }
  std::vector<bool> free(6);
  for (int q = 0; q < 6; ++q) free[q] = !held[q];
  solve_free(a, rhs, free, x);
  RigidMotion r;
  for (int d = 0; d < 3; ++d) {
    r.U[d] = x[d];
    r.w[d] = x[3 + d];
  }
  return r;
}

}  // namespace eulerfsi
