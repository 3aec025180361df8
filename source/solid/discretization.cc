#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/numerics/vector_tools.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/geometry/geometry.h>
#include <tissuefem/solid/discretization.h>

namespace tissuefem::solid
{
  void
  FiniteElementParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Finite element");
    prm.declare_entry("Polynomial degree",
                      "1",
                      Patterns::Integer(1, 3),
                      "Degree k of the Lagrange elements: Q_k (k = 1..3) on "
                      "quadrilaterals/hexahedra, P_k (k = 1, 2) on "
                      "triangles/tetrahedra.");
    prm.declare_entry("Quadrature points",
                      "0",
                      Patterns::Integer(0, 6),
                      "Gauss points per direction (for simplices: the "
                      "simplex Gauss rule with that many points per "
                      "direction, at most 4); 0 chooses degree + 1.");
    prm.declare_entry(
      "Element kernel",
      "automatic",
      Patterns::Selection("automatic|general"),
      "'automatic': linear triangles and tetrahedra in the displacement "
      "formulation use the lean kernel (one stress and tangent evaluation "
      "per cell from cached shape gradients, closed-form P1 mass, cells "
      "batched per material, rows added in parallel; "
      "solid/linear_simplex_kernel.h), every other element the general "
      "quadrature loop. 'general': the quadrature loop everywhere (the "
      "reference the lean kernel is tested against; same results to "
      "round-off, several times slower on tetrahedra).");
    prm.declare_entry(
      "Mass",
      "consistent",
      Patterns::Selection("consistent|lumped"),
      "The mass matrix of the equations of motion as the implicit "
      "integrators (backward Euler, the linearly implicit Euler, the "
      "quasi-Newton backward Euler, quasistatics' reactions) and the "
      "kinetic energy, reaction and held forces use it: 'consistent' "
      "(int rho N_a N_b dV) or 'lumped' (its row sums int rho N_a dV on the "
      "diagonal, SOFA's DiagonalMass; Jeffrey's explicit scheme's mass). "
      "Lumping lowers the frequencies of the discrete body (the consistent "
      "mass overestimates them, the lumped one underestimates them: a "
      "single linear bar element has omega^2 = 3 E/(rho L^2) consistent, 2 "
      "E/(rho L^2) lumped) and makes the inertial term diagonal. Explicit and "
      "first-order integrators (damped central difference, Radau IIA, "
      "ARKode) step with the lumped mass whatever this says; the kinetic "
      "energy and forces they report follow it. 'lumped' needs P1 or Q_k "
      "elements: row sums of the P2 simplex's mass are not positive.");
    prm.leave_subsection();
  }


  void
  FiniteElementParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Finite element");
    degree            = prm.get_integer("Polynomial degree");
    quadrature_points = prm.get_integer("Quadrature points");
    lean_kernel       = prm.get("Element kernel") == "automatic";
    lumped_mass       = prm.get("Mass") == "lumped";
    prm.leave_subsection();
  }


  template <int dim>
  Discretization<dim>::Discretization(const Triangulation<dim> &triangulation,
                                      const FiniteElementParameters &parameters,
                                      const unsigned int n_components)
      : dof_handler(triangulation)
      , simplex(geometry::is_simplex_mesh(triangulation))
      , lean_kernel(parameters.lean_kernel)
      , lumped_mass(parameters.lumped_mass)
  {
    const unsigned int k = parameters.degree;
    const unsigned int n_q
      = parameters.quadrature_points > 0 ? parameters.quadrature_points : k + 1;
    if (simplex)
      {
        // deal.II 9.4 has simplex Lagrange elements up to degree 2 and
        // simplex Gauss rules up to 4 points per direction.
        require(k <= 2,
                "Finite element/Polynomial degree",
                "must be 1 or 2 on triangles/tetrahedra (deal.II 9.4), got "
                  + std::to_string(k));
        require(n_q <= 4,
                "Finite element/Quadrature points",
                "must be at most 4 on triangles/tetrahedra, got "
                  + std::to_string(n_q));
        // Row sums of the P2 simplex's mass are zero (triangle) or negative
        // (tetrahedron) at the vertices.
        require(k == 1 || !lumped_mass,
                "Finite element/Mass",
                "'lumped' needs linear triangles or tetrahedra (the P2 "
                "simplex's row sums are not positive); use 'consistent' "
                "with Polynomial degree = 2");
        fe = std::make_unique<FESystem<dim>>(FE_SimplexP<dim>(k), n_components);
        mapping         = std::make_unique<MappingFE<dim>>(FE_SimplexP<dim>(1));
        cell_quadrature = QGaussSimplex<dim>(n_q);
        if constexpr (dim == 3)
          face_quadrature = QGaussSimplex<dim - 1>(n_q);
        else
          face_quadrature = QGauss<dim - 1>(n_q);
      }
    else
      {
        fe      = std::make_unique<FESystem<dim>>(FE_Q<dim>(k), n_components);
        mapping = std::make_unique<MappingQ<dim>>(1);
        cell_quadrature = QGauss<dim>(n_q);
        face_quadrature = QGauss<dim - 1>(n_q);
      }
    distribute(nullptr);
  }


  template <int dim>
  void
  Discretization<dim>::distribute(
    const boundary::BoundaryConditions<dim> *boundary_conditions,
    const std::vector<unsigned int>         *held_vertices)
  {
    dof_handler.distribute_dofs(*fe);
    locally_owned = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant);

    hanging_node_constraints.clear();
    hanging_node_constraints.reinit(locally_relevant);
    DoFTools::make_hanging_node_constraints(dof_handler,
                                            hanging_node_constraints);
    hanging_node_constraints.close();
    has_hanging_nodes
      = Utilities::MPI::max(hanging_node_constraints.n_constraints() > 0 ? 1
                                                                         : 0,
                            parallel_tools::communicator())
        == 1;

    constraints.clear();
    constraints.reinit(locally_relevant);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints);
    if (boundary_conditions)
      for (const auto &d : boundary_conditions->dirichlet)
        VectorTools::interpolate_boundary_values(*mapping,
                                                 dof_handler,
                                                 d.id,
                                                 Functions::ZeroFunction<dim>(
                                                   fe->n_components()),
                                                 constraints,
                                                 d.mask);
    if (held_vertices)
      for (const auto &[dof, vertex, component] :
           held_vertex_dofs(dof_handler, *held_vertices, locally_relevant))
        if (!constraints.is_constrained(dof))
          constraints.add_line(dof);
    constraints.close();
  }


  template <int dim>
  std::vector<std::tuple<types::global_dof_index, unsigned int, unsigned int>>
  held_vertex_dofs(const DoFHandler<dim>           &dof_handler,
                   const std::vector<unsigned int> &vertices,
                   const IndexSet                  &relevant)
  {
    std::vector<bool> wanted(dof_handler.get_triangulation().n_vertices(),
                             false);
    for (const auto v : vertices)
      wanted[v] = true;
    std::vector<std::tuple<types::global_dof_index, unsigned int, unsigned int>>
      result;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        for (const auto v : cell->vertex_indices())
          if (wanted[cell->vertex_index(v)])
            for (unsigned int c = 0; c < dim; ++c)
              {
                const auto dof = cell->vertex_dof_index(v, c);
                if (relevant.is_element(dof))
                  result.emplace_back(dof, cell->vertex_index(v), c);
              }
    std::sort(result.begin(), result.end());
    result.erase(std::unique(result.begin(), result.end()), result.end());
    return result;
  }


  template <int dim>
  void
  Discretization<dim>::initialize_vector(VectorType &v,
                                         const bool  ghosted) const
  {
    if (ghosted)
      v.reinit(locally_owned, locally_relevant, parallel_tools::communicator());
    else
      v.reinit(locally_owned, parallel_tools::communicator());
  }


  template <int dim>
  void
  Discretization<dim>::initialize_assembly_vector(VectorType &v) const
  {
    // The owned rows only: rows owned elsewhere go to Epetra_FEVector's own
    // list of the entries actually written, which compress() sends: the
    // layer of rows shared with other processes. A vector made writable on
    // the locally relevant rows instead exports all of them at every
    // compress(), and on a shared mesh (every cell a ghost) those are all
    // rows: an explicit step on two processes took as long as on one
    // (doc/studies.md, Step time against size). Writes outside that set
    // would also be unchecked in Release builds.
    initialize_vector(v);
  }

  template <int dim>
  std::vector<VectorType>
  Discretization<dim>::rigid_body_modes() const
  {
    std::map<types::global_dof_index, Point<dim>> points;
    DoFTools::map_dofs_to_support_points(*mapping, dof_handler, points);
    const unsigned int      n_rotations = dim * (dim - 1) / 2;
    std::vector<VectorType> modes(dim + n_rotations);
    for (auto &mode : modes)
      initialize_vector(mode);
    // The component of each dof: from the cells (a dof's component is the
    // same on every cell that has it).
    std::vector<types::global_dof_index> dofs(fe->n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            if (locally_owned.is_element(dofs[i]))
              {
                const unsigned int c = fe->system_to_component_index(i).first;
                const Point<dim>  &x = points[dofs[i]];
                modes[c][dofs[i]]    = 1.;
                // Rotation about axis r maps x to e_r x x.
                if constexpr (dim == 2)
                  modes[2][dofs[i]] = (c == 0 ? -x[1] : x[0]);
                if constexpr (dim == 3)
                  {
                    const double rotation[3][3]
                      = {{0, -x[2], x[1]}, {x[2], 0, -x[0]}, {-x[1], x[0], 0}};
                    for (unsigned int r = 0; r < 3; ++r)
                      modes[3 + r][dofs[i]] = rotation[r][c];
                  }
              }
        }
    for (auto &mode : modes)
      mode.compress(VectorOperation::insert);
    return modes;
  }

  template std::vector<
    std::tuple<types::global_dof_index, unsigned int, unsigned int>>
  held_vertex_dofs(const DoFHandler<1> &,
                   const std::vector<unsigned int> &,
                   const IndexSet &);
  template std::vector<
    std::tuple<types::global_dof_index, unsigned int, unsigned int>>
  held_vertex_dofs(const DoFHandler<2> &,
                   const std::vector<unsigned int> &,
                   const IndexSet &);
  template std::vector<
    std::tuple<types::global_dof_index, unsigned int, unsigned int>>
  held_vertex_dofs(const DoFHandler<3> &,
                   const std::vector<unsigned int> &,
                   const IndexSet &);
  template class Discretization<1>;
  template class Discretization<2>;
  template class Discretization<3>;
} // namespace tissuefem::solid
