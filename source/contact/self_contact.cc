#include <deal.II/base/mpi.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/contact/self_contact.h>
#include <tissuefem/solid/self_overlap.h>

#include <algorithm>
#include <cmath>

namespace tissuefem::contact
{
  namespace
  {
    /// The overlap density phi of self_contact.h: how many coverings of a
    /// point with winding number @p w are too many or negative.
    double
    excess_coverings(const double w)
    {
      return std::max(w - 1, 0.) + std::max(-w, 0.);
    }

    /// dim! (the simplex volume is the determinant over it).
    constexpr double
    factorial(const int n)
    {
      return n <= 1 ? 1. : n * factorial(n - 1);
    }

    /// The Levi-Civita symbol of (a, b, c), each in 0..2.
    double
    levi_civita(const unsigned int a,
                const unsigned int b,
                const unsigned int c)
    {
      return 0.5 * (double(a) - b) * (double(b) - c) * (double(c) - a);
    }
  } // namespace


  template <int dim>
  SelfContact<dim>::SelfContact(
    const solid::Discretization<dim> &discretization,
    const double                      pressure,
    const bool                        tangent)
      : discretization(discretization)
      , pressure(pressure)
      , tangent(tangent)
  {
    // Facets name dofs of the current mesh: a new mesh waits for the next
    // step's start.
    mesh_changed = discretization.dof_handler.get_triangulation()
                     .signals.any_change.connect([this]() { facets.clear(); });
  }


  template <int dim>
  void
  SelfContact<dim>::begin_step(const VectorType &u, const double)
  {
    facets.clear();
    const auto                      &dof_handler = discretization.dof_handler;
    const solid::BoundaryFacets<dim> all
      = solid::gather_boundary_facets(dof_handler, u);
    unsigned int k = all.first_local;
    solid::for_each_boundary_piece(
      dof_handler, [&](const auto &face, const auto &piece) {
        std::array<Point<dim>, dim> x;
        Facet                       facet;
        facet.centre = Point<dim>();
        for (unsigned int i = 0; i < dim; ++i)
          {
            for (unsigned int c = 0; c < dim; ++c)
              {
                x[i][c] = all.coordinates[(k * dim + i) * dim + c];
                facet.dofs[i * dim + c] = face->vertex_dof_index(piece[i], c);
              }
            facet.X[i] = face->vertex(piece[i]);
            facet.centre += x[i] / dim;
          }
        const double w
          = solid::winding_number(facet.centre, all.coordinates, k);
        ++k;
        facet.weight = excess_coverings(w + 0.5) - excess_coverings(w - 0.5);
        // An untangled body's facets see w_f = 1/2 up to the round-off of
        // the solid angles: they push nothing, and cost nothing.
        if (std::abs(facet.weight) < 1e-9)
          return;
        determinant(facet, u, facet.start_gradient, nullptr);
        for (double &g : facet.start_gradient)
          g *= dim * pressure * facet.weight / factorial(dim);
        facets.push_back(facet);
      });
  }


  template <int dim>
  double
  SelfContact<dim>::determinant(const Facet                   &facet,
                                const VectorType              &u,
                                std::array<double, dim * dim> &gradient,
                                FullMatrix<double>            *hessian) const
  {
    std::array<Tensor<1, dim>, dim> y;
    for (unsigned int i = 0; i < dim; ++i)
      {
        y[i] = facet.X[i] - facet.centre;
        for (unsigned int c = 0; c < dim; ++c)
          y[i][c] += u[facet.dofs[i * dim + c]];
      }
    if constexpr (dim == 2)
      {
        // det [y0; y1] = y0 x y1 (the cross product's z component).
        gradient = {{y[1][1], -y[1][0], -y[0][1], y[0][0]}};
        if (hessian)
          for (unsigned int a = 0; a < 2; ++a)
            for (unsigned int b = 0; b < 2; ++b)
              {
                const double e       = a == b ? 0. : a == 0 ? 1. : -1.;
                (*hessian)(a, 2 + b) = e;
                (*hessian)(2 + b, a) = e;
              }
        return y[0][0] * y[1][1] - y[0][1] * y[1][0];
      }
    if constexpr (dim == 3)
      {
        // det = y0 . (y1 x y2); its derivative by y_i is y_j x y_k and by
        // y_i, y_j the symbol contracted with y_k, (i, j, k) cyclic.
        for (unsigned int i = 0; i < 3; ++i)
          {
            const Tensor<1, 3> g
              = cross_product_3d(y[(i + 1) % 3], y[(i + 2) % 3]);
            for (unsigned int c = 0; c < 3; ++c)
              gradient[i * 3 + c] = g[c];
            if (hessian)
              {
                const unsigned int j = (i + 1) % 3, k = (i + 2) % 3;
                for (unsigned int a = 0; a < 3; ++a)
                  for (unsigned int b = 0; b < 3; ++b)
                    {
                      double e = 0;
                      for (unsigned int c = 0; c < 3; ++c)
                        e += levi_civita(a, b, c) * y[k][c];
                      (*hessian)(i * 3 + a, j * 3 + b) = e;
                      (*hessian)(j * 3 + b, i * 3 + a) = e;
                    }
              }
          }
        return y[0] * cross_product_3d(y[1], y[2]);
      }
    (void)facet;
    (void)u;
    (void)gradient;
    (void)hessian;
    return 0;
  }


  template <int dim>
  void
  SelfContact<dim>::add(const VectorType                &u,
                        const double                     time,
                        const bool                       jacobian,
                        const AffineConstraints<double> &rows,
                        const bool                       inhomogeneous,
                        MatrixType                      &matrix,
                        VectorType                      &residual) const
  {
    (void)time;
    constexpr unsigned int n = dim * dim;
    // E_f = s det, s = dim p_c c / dim! (the simplex volume is det / dim!).
    std::array<double, n>                gradient{};
    FullMatrix<double>                   K(n, n);
    Vector<double>                       r(n);
    std::vector<types::global_dof_index> dofs(n);
    for (const Facet &facet : facets)
      {
        if (!tangent)
          {
            // The dead load of the step's start.
            for (unsigned int i = 0; i < n; ++i)
              {
                r(i)    = facet.start_gradient[i];
                dofs[i] = facet.dofs[i];
              }
            rows.distribute_local_to_global(r, dofs, residual);
            continue;
          }
        const double s = dim * pressure * facet.weight / factorial(dim);
        K              = 0;
        determinant(facet, u, gradient, jacobian ? &K : nullptr);
        for (unsigned int i = 0; i < n; ++i)
          {
            r(i)    = s * gradient[i];
            dofs[i] = facet.dofs[i];
          }
        if (jacobian)
          {
            K *= s;
            rows.distribute_local_to_global(
              K, r, dofs, matrix, residual, inhomogeneous);
          }
        else
          rows.distribute_local_to_global(r, dofs, residual);
      }
  }


  template <int dim>
  double
  SelfContact<dim>::energy(const VectorType &u, const double) const
  {
    std::array<double, dim * dim> gradient{};
    double                        sum = 0;
    for (const Facet &facet : facets)
      if (tangent)
        sum += dim * pressure * facet.weight / factorial(dim)
               * determinant(facet, u, gradient, nullptr);
      else
        for (unsigned int i = 0; i < dim * dim; ++i)
          sum += facet.start_gradient[i] * u[facet.dofs[i]];
    return Utilities::MPI::sum(sum, parallel_tools::communicator());
  }


  template class SelfContact<1>;
  template class SelfContact<2>;
  template class SelfContact<3>;
} // namespace tissuefem::contact
