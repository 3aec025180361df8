#pragma once

#include <deal.II/base/exceptions.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <algorithm>
#include <vector>

namespace tissuefem::solid
{
  using namespace dealii;

  /**
   * In-place access to a compressed Trilinos matrix's rows, for assemblies
   * that add a cell's entries without deal.II's search per entry (Solid's
   * and the nodal dilatation system's): the values of each locally owned
   * row (valid while the sparsity pattern is), and where a column lies in a
   * row.
   */
  inline std::vector<double *>
  row_value_pointers(const TrilinosWrappers::SparseMatrix &matrix)
  {
    const auto           &M = matrix.trilinos_matrix();
    std::vector<double *> values(M.NumMyRows());
    for (int r = 0; r < M.NumMyRows(); ++r)
      {
        int  length;
        int *columns;
        M.ExtractMyRowView(r, length, values[r], columns);
      }
    return values;
  }

  /// The position of global column @p column among the entries of the
  /// locally owned row @p row (local index); the entry must exist.
  inline int
  entry_in_row(const TrilinosWrappers::SparseMatrix &matrix,
               const int                             row,
               const types::global_dof_index         column)
  {
    const auto &M = matrix.trilinos_matrix();
    int         length;
    double     *values;
    int        *columns;
    M.ExtractMyRowView(row, length, values, columns);
    const int local
      = M.ColMap().LID(static_cast<TrilinosWrappers::types::int_type>(column));
    const int *found = std::find(columns, columns + length, local);
    AssertThrow(local >= 0 && found != columns + length, ExcInternalError());
    return found - columns;
  }
} // namespace tissuefem::solid
