#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <tissuefem/time/nodal.h>
#include <tissuefem/time/radau_linear_systems.h>

#include <Epetra_CrsMatrix.h>

#include <complex>
#include <vector>

namespace tissuefem::time
{
  RadauLinearSystems::RadauLinearSystems(const double damping,
                                         const double gamma_hat,
                                         const double alpha_hat,
                                         const double beta_hat)
      : damping(damping)
      , gamma_hat(gamma_hat)
      , alpha_hat(alpha_hat)
      , beta_hat(beta_hat)
  {
  }


  void
  RadauLinearSystems::reinit(const VectorType      &mass,
                             const VectorType      &free,
                             const bool             assembled,
                             solvers::LinearSolver &real_solver)
  {
    this->mass           = &mass;
    this->free           = &free;
    this->assembled      = assembled;
    this->real_solver    = &real_solver;
    const IndexSet owned = mass.locally_owned_elements();
    n_dofs               = owned.size();
    doubled              = IndexSet(2 * n_dofs);
    doubled.add_indices(owned);
    doubled.add_indices(owned, n_dofs);
    // The old matrices' layout is gone.
    complex_solver.reset();
    real_refactorize = complex_refactorize = true;
  }


  void
  RadauLinearSystems::factorize(const Stiffness &stiffness,
                                const double     step,
                                const bool       with_complex)
  {
    const double *m       = local_entries(*mass);
    const double *is_free = local_entries(*free);
    const auto   &K       = stiffness.matrix().trilinos_matrix();
    const auto    n       = n_dofs;

    // Real: K + s M, s = sigma (sigma + c), sigma = gamma_hat / h.
    const double sigma = gamma_hat / step;
    const double s     = sigma * (sigma + damping);
    real_matrix.copy_from(stiffness.matrix());
    {
      auto &R = const_cast<Epetra_CrsMatrix &>(real_matrix.trilinos_matrix());
      for (int r = 0; r < R.NumMyRows(); ++r)
        if (is_free[r] > 0)
          {
            int     length;
            double *values;
            int    *columns;
            R.ExtractMyRowView(r, length, values, columns);
            for (int k = 0; k < length; ++k)
              if (R.ColMap().GID(columns[k]) == R.RowMap().GID(r))
                values[k] += s * m[r];
          }
    }
    real_refactorize = true;
    if (!with_complex)
      return;

    // Complex: K + (p + iq) M as [K + pM, -qM; qM, K + pM] on rows i and
    // i + n.
    const std::complex<double> sc(alpha_hat / step, beta_hat / step);
    const std::complex<double> ss = sc * (sc + damping);
    const double               p = ss.real(), q = ss.imag();
    const bool                 first = complex_solver == nullptr;
    if (first)
      {
        TrilinosWrappers::SparsityPattern pattern(
          doubled, doubled, parallel_tools::communicator());
        for (int r = 0; r < K.NumMyRows(); ++r)
          {
            int     length;
            double *values;
            int    *columns;
            K.ExtractMyRowView(r, length, values, columns);
            const types::global_dof_index        row = K.RowMap().GID(r);
            std::vector<types::global_dof_index> cols(length), shifted(length);
            for (int k = 0; k < length; ++k)
              {
                cols[k]    = K.ColMap().GID(columns[k]);
                shifted[k] = cols[k] + n;
              }
            cols.push_back(row + n);
            shifted.push_back(row);
            pattern.add_entries(row, cols.begin(), cols.end());
            pattern.add_entries(row + n, shifted.begin(), shifted.end());
          }
        pattern.compress();
        complex_matrix.reinit(pattern);
        // The 2n system is not symmetric: always a direct solver.
        complex_solver = solvers::LinearSolver::with_defaults("MUMPS");
      }
    for (int r = 0; r < K.NumMyRows(); ++r)
      {
        int     length;
        double *values;
        int    *columns;
        K.ExtractMyRowView(r, length, values, columns);
        const types::global_dof_index        row = K.RowMap().GID(r);
        std::vector<types::global_dof_index> cols(length + 1),
          shifted(length + 1);
        std::vector<double> entries(length + 1);
        for (int k = 0; k < length; ++k)
          {
            cols[k]    = K.ColMap().GID(columns[k]);
            shifted[k] = cols[k] + n;
            entries[k] = values[k];
            if (cols[k] == row && is_free[r] > 0)
              entries[k] += p * m[r];
          }
        const double coupling = is_free[r] > 0 ? q * m[r] : 0.;
        cols[length]          = row + n;
        entries[length]       = -coupling;
        complex_matrix.set(row, cols.size(), cols.data(), entries.data());
        shifted[length] = row;
        entries[length] = coupling;
        complex_matrix.set(row + n,
                           shifted.size(),
                           shifted.data(),
                           entries.data());
      }
    complex_matrix.compress(VectorOperation::insert);
    complex_refactorize = true;
  }


  void
  RadauLinearSystems::solve_real(const double step,
                                 VectorType  &ru,
                                 VectorType  &rv)
  {
    const double  sigma = gamma_hat / step;
    const double  s     = sigma * (sigma + damping);
    const double *m = local_entries(*mass), *is_free = local_entries(*free);
    double       *xu = local_entries(ru), *xv = local_entries(rv);
    const unsigned int n = local_size(ru);
    if (!assembled)
      {
        for (unsigned int i = 0; i < n; ++i)
          {
            const double x
              = is_free[i] * (xv[i] + (sigma + damping) * xu[i]) / s;
            xv[i] = sigma * x - is_free[i] * xu[i];
            xu[i] = x;
          }
        return;
      }
    VectorType b(ru), x(ru);
    double    *bp = local_entries(b);
    for (unsigned int i = 0; i < n; ++i)
      bp[i] = is_free[i] * m[i] * (xv[i] + (sigma + damping) * xu[i]);
    x = 0.;
    real_solver->solve(real_matrix, x, b, real_refactorize);
    real_refactorize = false;
    const double *xp = local_entries(x);
    for (unsigned int i = 0; i < n; ++i)
      {
        xv[i] = sigma * xp[i] - is_free[i] * xu[i];
        xu[i] = xp[i];
      }
  }


  void
  RadauLinearSystems::solve_complex(const double step,
                                    VectorType  &ru,
                                    VectorType  &rv,
                                    VectorType  &su,
                                    VectorType  &sv)
  {
    using C                    = std::complex<double>;
    const C            sigma   = C(alpha_hat, beta_hat) / step;
    const C            s       = sigma * (sigma + damping);
    const double      *m       = local_entries(*mass);
    const double      *is_free = local_entries(*free);
    double            *pu = local_entries(ru), *pv = local_entries(rv);
    double            *qu = local_entries(su), *qv = local_entries(sv);
    const unsigned int n = local_size(ru);
    std::vector<C>     x(n);
    if (!assembled)
      for (unsigned int i = 0; i < n; ++i)
        x[i] = is_free[i]
               * (C(pv[i], qv[i]) + (sigma + damping) * C(pu[i], qu[i])) / s;
    else
      {
        VectorType b(doubled, parallel_tools::communicator()), y(b);
        double    *bp = local_entries(b);
        for (unsigned int i = 0; i < n; ++i)
          {
            const C rhs
              = is_free[i] * m[i]
                * (C(pv[i], qv[i]) + (sigma + damping) * C(pu[i], qu[i]));
            bp[i]     = rhs.real();
            bp[i + n] = rhs.imag();
          }
        complex_solver->solve(complex_matrix, y, b, complex_refactorize);
        complex_refactorize = false;
        const double *yp    = local_entries(y);
        for (unsigned int i = 0; i < n; ++i)
          x[i] = C(yp[i], yp[i + n]);
      }
    for (unsigned int i = 0; i < n; ++i)
      {
        const C v = sigma * x[i] - is_free[i] * C(pu[i], qu[i]);
        pu[i]     = x[i].real();
        qu[i]     = x[i].imag();
        pv[i]     = v.real();
        qv[i]     = v.imag();
      }
  }
} // namespace tissuefem::time
