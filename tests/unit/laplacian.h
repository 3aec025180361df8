// The matrices the linear-solver tests solve: the five-point Laplacian of
// an m x m grid (or a 1D chain), its rows split among the processes.
#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <tissuefem/base/parallel.h>

#include "../tests.h"

#include <cstdint>

namespace tissuefem_tests
{
  using namespace dealii;
  using tissuefem::MatrixType;
  using tissuefem::VectorType;

  /// The rows this process owns of @p n, in one contiguous range.
  inline IndexSet
  owned_rows(const unsigned int n)
  {
    const unsigned int p = Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
    const unsigned int r = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
    IndexSet           owned(n);
    owned.add_range(n * r / p, n * (r + 1) / p);
    return owned;
  }

  /// The m x m five-point Laplacian (4 on the diagonal, -1 to each grid
  /// neighbour; Dirichlet rows implied outside) times @p scale plus
  /// @p shift on the diagonal; m = 1 row of a grid is a 1D chain when
  /// @p chain. @p skew != 0 adds a centred convection term along x
  /// (-skew to the left neighbour, +skew to the right): not symmetric.
  inline void
  laplacian(MatrixType        &A,
            const unsigned int m,
            const bool         chain,
            const double       scale,
            const double       shift,
            const double       skew = 0)
  {
    const unsigned int n     = chain ? m : m * m;
    const IndexSet     owned = owned_rows(n);
    if (A.m() != n)
      {
        TrilinosWrappers::SparsityPattern pattern(owned, MPI_COMM_WORLD);
        for (const auto i : owned)
          for (const long j : {long(i) - long(m),
                               long(i) - 1,
                               long(i),
                               long(i) + 1,
                               long(i) + long(m)})
            if (j >= 0 && j < long(n))
              pattern.add(i, j);
        pattern.compress();
        A.reinit(pattern);
      }
    for (const auto i : owned)
      {
        const unsigned int x = chain ? i : i % m, y = chain ? 0 : i / m;
        A.set(i, i, (chain ? 2. : 4.) * scale + shift);
        if (x > 0)
          A.set(i, i - 1, -scale - skew);
        if (x + 1 < m)
          A.set(i, i + 1, -scale + skew);
        if (!chain && y > 0)
          A.set(i, i - m, -scale);
        if (!chain && y + 1 < m)
          A.set(i, i + m, -scale);
      }
    A.compress(VectorOperation::insert);
  }


  /// A random vector in [1, 3) of A's row layout (the same on any number
  /// of processes: drawn for every row, kept for the owned ones).
  inline VectorType
  random_vector(const MatrixType &A, const std::uint64_t seed)
  {
    const IndexSet owned = owned_rows(A.m());
    VectorType     x(owned, MPI_COMM_WORLD);
    Random         random(seed);
    for (unsigned int i = 0; i < A.m(); ++i)
      {
        const double value = 2. + random.uniform();
        if (owned.is_element(i))
          x[i] = value;
      }
    x.compress(VectorOperation::insert);
    return x;
  }

  /// max |x - exact| / max |exact|.
  inline double
  relative_error(const VectorType &x, const VectorType &exact)
  {
    VectorType difference = x;
    difference -= exact;
    return difference.linfty_norm() / exact.linfty_norm();
  }
} // namespace tissuefem_tests
