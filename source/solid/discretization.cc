#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/fe/mapping_q.h>

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
    prm.leave_subsection();
  }


  void
  FiniteElementParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Finite element");
    degree            = prm.get_integer("Polynomial degree");
    quadrature_points = prm.get_integer("Quadrature points");
    prm.leave_subsection();
  }


  template <int dim>
  Discretization<dim>::Discretization(const Triangulation<dim> &triangulation,
                                      const FiniteElementParameters &parameters,
                                      const unsigned int n_components)
      : dof_handler(triangulation)
      , simplex(geometry::is_simplex_mesh(triangulation))
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
    dof_handler.distribute_dofs(*fe);
  }

  template class Discretization<1>;
  template class Discretization<2>;
  template class Discretization<3>;
} // namespace tissuefem::solid
