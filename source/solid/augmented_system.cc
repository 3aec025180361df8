#include <deal.II/base/exceptions.h>
#include <deal.II/lac/trilinos_index_access.h>

#include <tissuefem/solid/augmented_system.h>
#include <tissuefem/solid/matrix_rows.h>

#include <cstring>

namespace tissuefem::solid
{
  IndexSet
  vertex_set(const IndexSet &dofs, const unsigned int dim)
  {
    IndexSet vertices(dofs.size() / dim);
    for (const auto i : dofs)
      if (i % dim == 0)
        vertices.add_index(i / dim);
    vertices.compress();
    return vertices;
  }


  IndexSet
  with_vertex_unknowns(const IndexSet    &dofs,
                       const unsigned int dim,
                       const unsigned int copies)
  {
    const IndexSet                vertices   = vertex_set(dofs, dim);
    const types::global_dof_index n_vertices = vertices.size();
    IndexSet                      result(dofs.size() + copies * n_vertices);
    result.add_indices(dofs);
    for (unsigned int k = 0; k < copies; ++k)
      result.add_indices(vertices, dofs.size() + k * n_vertices);
    result.compress();
    return result;
  }


  void
  copy_dirichlet_lines(const AffineConstraints<double> &from,
                       const IndexSet                  &relevant,
                       AffineConstraints<double>       &to)
  {
    to.clear();
    to.reinit(relevant);
    for (const auto &line : from.get_lines())
      if (relevant.is_element(line.index))
        {
          AssertThrow(line.entries.empty(), ExcInternalError());
          to.add_line(line.index);
          to.set_inhomogeneity(line.index, line.inhomogeneity);
        }
    to.close();
  }


  void
  add_block(const MatrixType &from,
            MatrixType       &to,
            std::vector<int> &row,
            std::vector<int> &entry)
  {
    const Epetra_CrsMatrix &source = from.trilinos_matrix();
    if (entry.empty())
      {
        // Row r of @p from is row row[r] of @p to; its entries are among
        // that row's.
        const Epetra_CrsMatrix &target = to.trilinos_matrix();
        row.resize(source.NumMyRows());
        for (int r = 0; r < source.NumMyRows(); ++r)
          {
            row[r] = target.RowMap().LID(
              TrilinosWrappers::global_row_index(source, r));
            int     length;
            double *values;
            int    *local;
            source.ExtractMyRowView(r, length, values, local);
            for (int j = 0; j < length; ++j)
              entry.push_back(entry_in_row(
                to,
                row[r],
                TrilinosWrappers::global_column_index(source, local[j])));
          }
      }
    const std::vector<double *> into = row_value_pointers(to);
    for (int r = 0, k = 0; r < source.NumMyRows(); ++r)
      {
        int     length;
        double *values;
        int    *local;
        source.ExtractMyRowView(r, length, values, local);
        for (int j = 0; j < length; ++j, ++k)
          into[row[r]][entry[k]] += values[j];
      }
  }


  void
  finish_augmented(MatrixType       &matrix,
                   VectorType       &lifted,
                   const MatrixType *uu,
                   std::vector<int> &row,
                   std::vector<int> &entry,
                   VectorType       &residual)
  {
    matrix.compress(VectorOperation::add);
    lifted.compress(VectorOperation::add);
    if (uu)
      add_block(*uu, matrix, row, entry);
    // The displacement rows come first among the owned unknowns of the
    // augmented system and are all of @p residual's.
    const unsigned int n_owned_u = residual.locally_owned_size();
    double            *into      = residual.trilinos_vector()[0];
    const double      *elastic   = lifted.trilinos_vector()[0];
    for (unsigned int i = 0; i < n_owned_u; ++i)
      into[i] += elastic[i];
  }


  void
  solve_augmented(solvers::LinearSolver &solver,
                  const MatrixType      &matrix,
                  VectorType            &lifted,
                  const IndexSet        &owned,
                  VectorType            &x,
                  const VectorType      &b,
                  const bool             refactorize)
  {
    VectorType         B(owned, parallel_tools::communicator());
    VectorType         X(owned, parallel_tools::communicator());
    const unsigned int n_owned_u = b.locally_owned_size();
    double            *into      = B.trilinos_vector()[0];
    double            *rest      = lifted.trilinos_vector()[0];
    AssertDimension(static_cast<unsigned int>(x.trilinos_vector().MyLength()),
                    n_owned_u);
    std::memcpy(into, b.trilinos_vector()[0], n_owned_u * sizeof(double));
    for (unsigned int i = n_owned_u; i < B.locally_owned_size(); ++i)
      into[i] = -rest[i];
    solver.solve(matrix, X, B, refactorize);
    for (unsigned int i = n_owned_u; i < B.locally_owned_size(); ++i)
      rest[i] = 0;
    std::memcpy(x.trilinos_vector()[0],
                X.trilinos_vector()[0],
                n_owned_u * sizeof(double));
  }
} // namespace tissuefem::solid
