#include "sphstab/distributed/distributed_rate_form.hpp"

#include <petscsys.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace sphstab {

template <int Dim>
RateFormBlock distribute_rate_form(RateFormScheme<Dim>& scheme) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  const NeighbourList& nl = scheme.discretisation().neighbours;
  const int n = scheme.discretisation().size();
  if (ranks > n)
    throw std::invalid_argument("distribute_rate_form: " + std::to_string(ranks) + " ranks for " + std::to_string(n) +
                                " particles (at most one rank per particle)");
  // Block r ends at the first particle whose list entries reach (r + 1) / ranks of the total; never empty.
  std::vector<int> start(ranks + 1, 0);
  start[ranks] = n;
  const double total = static_cast<double>(nl.offsets[n]);
  int i = 0;
  for (int r = 1; r < ranks; ++r) {
    const double target = total * r / ranks;
    while (i < n && static_cast<double>(nl.offsets[i]) < target) ++i;
    start[r] = std::clamp(i, start[r - 1] + 1, n - (ranks - r));
    i = start[r];
  }
  std::vector<int> counts(ranks), displs(ranks);
  for (int r = 0; r < ranks; ++r) {
    const auto [b, e] = scheme.state_range(start[r], start[r + 1]);
    displs[r] = b;
    counts[r] = e - b;
  }
  const int size = scheme.size();
  scheme.set_row_partition(start[rank], start[rank + 1], [counts, displs, size](Eigen::VectorXd& dydt) {
    if (dydt.size() != size) throw std::logic_error("distribute_rate_form: rate vector of the wrong size");
    MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, dydt.data(), counts.data(), displs.data(), MPI_DOUBLE,
                   PETSC_COMM_WORLD);
  });
  return {.first = start[rank],
          .last = start[rank + 1],
          .rank = rank,
          .ranks = ranks,
          .pairs = nl.offsets[start[rank + 1]] - nl.offsets[start[rank]]};
}

bool identical_on_all_ranks(const Eigen::VectorXd& v) {
  // Max and min over ranks of every entry's bit pattern (as unsigned integers): equal everywhere iff identical.
  const long n = v.size();
  long lo = n, hi = n;
  MPI_Allreduce(MPI_IN_PLACE, &hi, 1, MPI_LONG, MPI_MAX, PETSC_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &lo, 1, MPI_LONG, MPI_MIN, PETSC_COMM_WORLD);
  if (lo != hi) return false;
  std::vector<std::uint64_t> bits(n), mx(n), mn(n);
  for (long k = 0; k < n; ++k) std::memcpy(&bits[k], &v[k], sizeof(double));
  MPI_Allreduce(bits.data(), mx.data(), static_cast<int>(n), MPI_UINT64_T, MPI_MAX, PETSC_COMM_WORLD);
  MPI_Allreduce(bits.data(), mn.data(), static_cast<int>(n), MPI_UINT64_T, MPI_MIN, PETSC_COMM_WORLD);
  return mx == mn;
}

template RateFormBlock distribute_rate_form<1>(RateFormScheme<1>&);
template RateFormBlock distribute_rate_form<2>(RateFormScheme<2>&);

}  // namespace sphstab
