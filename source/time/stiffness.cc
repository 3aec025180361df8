#include <tissuefem/base/input_error.h>
#include <tissuefem/time/nodal.h>
#include <tissuefem/time/stiffness.h>

#include <Epetra_CrsMatrix.h>

#include <algorithm>

namespace tissuefem::time
{
  Stiffness::Stiffness(const std::string &kind)
      : kind(kind)
  {
    if (kind != "analytical" && kind != "numerical" && kind != "simplified")
      throw InputError("Jacobian kind '" + kind + "' is not one of "
                       + choices());
  }


  void
  Stiffness::evaluate(solid::Operators &solid,
                      const VectorType &u,
                      const double      time)
  {
    if (kind == "simplified")
      return;
    VectorType residual;
    if (!layout_ready || kind == "analytical")
      {
        // The solid's Jacobian with mass coefficient 0 is K(u); its layout
        // is also the pattern the differenced columns fill.
        solid.implicit_residual(u, u, 0., time, residual, true);
        stiffness.copy_from(solid.jacobian());
        layout_ready = true;
        if (kind == "analytical")
          return;
      }

    // Forward differences, one force evaluation per column group.
    const auto &groups = solid.column_groups();
    if (colour.size() != solid.n_dofs())
      {
        colour.assign(solid.n_dofs(), 0);
        for (unsigned int g = 0; g < groups.size(); ++g)
          for (const auto j : groups[g])
            colour[j] = g;
      }
    VectorType free, base, shifted, trial(u);
    solid.initialize_vector(free);
    free.add(1.);
    solid.zero_constrained_entries(free);
    solid.internal_force(u, base);
    const double      e = 1e-8 * solid.length_scale();
    Epetra_CrsMatrix &K
      = const_cast<Epetra_CrsMatrix &>(stiffness.trilinos_matrix());
    const auto    range   = u.local_range();
    const double *is_free = local_entries(free);
    for (unsigned int g = 0; g < groups.size(); ++g)
      {
        trial = u;
        for (const auto j : groups[g])
          if (j >= range.first && j < range.second
              && is_free[j - range.first] > 0)
            local_entries(trial)[j - range.first] += e;
        solid.internal_force(trial, shifted);
        const double *f  = local_entries(shifted);
        const double *f0 = local_entries(base);
        for (int r = 0; r < K.NumMyRows(); ++r)
          {
            int     length;
            double *values;
            int    *columns;
            K.ExtractMyRowView(r, length, values, columns);
            const auto row = K.RowMap().GID(r);
            for (int k = 0; k < length; ++k)
              {
                const auto column = K.ColMap().GID(columns[k]);
                if (colour[column] != g)
                  continue;
                const bool row_free = is_free[row - range.first] > 0;
                if (!row_free)
                  values[k] = (column == row) ? 1. : 0.;
                else
                  values[k] = (f[r] - f0[r]) / e;
              }
          }
      }
    // A constrained column is never perturbed, and no other column of its
    // group reaches its rows: it reads exactly 0, eliminated as in the
    // assembled tangent.
  }
} // namespace tissuefem::time
