#include <deal.II/base/mpi.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/contact/self_contact.h>
#include <tissuefem/solid/self_overlap.h>

#include <algorithm>
#include <cmath>
#include <sstream>

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


  template <int dim>
  void
  SelfContact<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary conditions");
    prm.declare_entry(
      "Self contact pressure",
      "automatic",
      Patterns::Anything(),
      "Overlap pressure p_c (Pa if SI; 0: off): where the deformed body "
      "overlaps itself, its boundary facets inside the body elsewhere are "
      "pushed back into their own part with the pressure p_c. This is "
      "the gradient of p_c times the volume the body covers more than "
      "once (contact/self_contact.h), so it resolves overlaps that are "
      "already there (a tangled crushed start, a fold-over) as well as "
      "new ones. Which facets push is decided at each step's start. "
      "Backward Euler, quasistatic and linearly implicit Euler runs only. "
      "'automatic': twice the shear modulus of the stiffest invertible "
      "neo-Hookean material where the mesh has triangles or tetrahedra "
      "(which, crushed, can settle tangled) and the integrator takes it, "
      "0 otherwise; the first lines of a run say which. Measured on 33 "
      "crushed starts (doc/tests.md): twice the shear modulus untangled "
      "all of them. Costs (boundary facets)^2 solid angles a step.");
    prm.declare_entry(
      "Self contact tangent",
      "false",
      Patterns::Bool(),
      "false: each overlapping facet's force at the step's start is held "
      "over the step (a dead load, no tangent). true: over a step each "
      "such facet has the energy of the cone from its centre at the "
      "step's start (contact/self_contact.h), so that Newton gets the "
      "tangent of its turning and stretching; measured on 33 crushed "
      "starts it untangled all of them at 1 to 1.3 times the shear "
      "modulus but made Newton fail on a third of them at twice it, "
      "where the dead load untangled all (doc/tests.md).");
    prm.leave_subsection();
  }


  template <int dim>
  std::unique_ptr<forces::Interface<dim>>
  SelfContact<dim>::create(ParameterHandler             &prm,
                           const forces::SceneData<dim> &scene)
  {
    const std::string name = "Boundary conditions/Self contact pressure";
    prm.enter_subsection("Boundary conditions");
    const std::string given = Utilities::trim(prm.get("Self contact pressure"));
    const bool        tangent = prm.get_bool("Self contact tangent");
    prm.leave_subsection();
    double      pressure = 0;
    std::string note;
    if (given == "automatic")
      {
        // Crushed tetrahedra (triangles) of the invertible model can
        // settle tangled, which elasticity holds (doc/tests.md, inversion
        // recovery); twice the shear modulus is the middle of the window
        // where every one of 33 crushed starts untangled. Hexahedra
        // recover by elasticity alone.
        double shear = 0;
        for (unsigned int m = 0; m < scene.materials.model_names.size(); ++m)
          if (scene.materials.model_names[m] == "invertible neo-Hookean")
            shear = std::max(shear, scene.materials.constants[m].mu);
        const bool simplices
          = !scene.discretization.dof_handler.get_triangulation()
               .all_reference_cells_are_hyper_cube();
        const bool takes = scene.can.begins_steps;
        note             = shear == 0 ? "no invertible neo-Hookean material"
                           : !simplices ? "the invertible model on quadrilaterals or "
                                          "hexahedra, which recover by elasticity alone"
                           : !takes
                             ? "integrator '" + scene.integrator + "' does not take it"
                             : "twice the shear modulus of the "
                               "invertible neo-Hookean model on "
                               "triangles or tetrahedra";
        note             = "automatic: " + note;
        pressure         = shear > 0 && simplices && takes ? 2 * shear : 0.;
      }
    else
      {
        const std::string must
          = "must be 'automatic' or a pressure >= 0 (0: off), not '" + given
            + "'";
        std::vector<double> value;
        try
          {
            value = parse_numbers(given, "Parameter '" + name + "'");
          }
        catch (const InputError &)
          {
            require(false, name, must);
          }
        require(value.size() == 1 && value[0] >= 0, name, must);
        pressure = value[0];
        // Its weights are taken where each step begins.
        if (pressure != 0)
          scene.refuse_unless(&forces::Capabilities::begins_steps,
                              name,
                              "needs");
      }
    std::ostringstream line;
    line << "self contact pressure p_c = " << pressure
         << " (stress units; 0: off" << (note.empty() ? "" : "; " + note)
         << ")";
    scene.notes.push_back(line.str());
    if (pressure == 0)
      return nullptr;
    return std::make_unique<SelfContact<dim>>(scene.discretization,
                                              pressure,
                                              tangent);
  }


  template class SelfContact<1>;
  template class SelfContact<2>;
  template class SelfContact<3>;

  TISSUEFEM_REGISTER_FORCE_CONTRIBUTION(
    SelfContact,
    "self contact",
    "the overlap pressure of 'Boundary conditions/Self contact pressure' "
    "(on when it is, or resolves to, a pressure > 0).")
} // namespace tissuefem::contact
