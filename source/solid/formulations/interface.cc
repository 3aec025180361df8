#include <deal.II/base/exceptions.h>

#include <tissuefem/solid/formulations/interface.h>

namespace tissuefem::solid::formulations
{
  template <int dim>
  CellTerms<dim>::CellTerms(const unsigned int n_scalar, const unsigned int n_q)
      : U(n_scalar)
      , F(n_q)
      , P(n_q)
      , A(n_q)
  {
  }


  template <int dim>
  CellTerms<dim>::CellTerms(const CellTerms &other)
      : U(other.U)
      , F(other.F)
      , P(other.P)
      , A(other.A)
      , own(other.own ? other.own->clone() : nullptr)
  {
  }


  template <int dim>
  void
  deformation_gradients(const CellCache<dim> &cache, CellTerms<dim> &cell)
  {
    for (unsigned int q = 0; q < cache.n_q; ++q)
      {
        Tensor<2, dim> &F = cell.F[q];
        F                 = unit_symmetric_tensor<dim>();
        for (unsigned int k = 0; k < cache.n_scalar; ++k)
          F += outer_product(cell.U[k], cache.gradient(cell.c, q, k));
      }
  }


  template <int dim>
  void
  check_inversion(CellTerms<dim> &cell)
  {
    // An inverted point (where the model cannot represent it) discards the
    // whole cell; the report gives the cell's smallest det F.
    if (cell.material->admits_inversion())
      return;
    for (const Tensor<2, dim> &F : cell.F)
      {
        const double det = determinant(F);
        if (det <= 0)
          cell.inverted_det = std::min(cell.inverted_det, det);
      }
  }


  template <int dim>
  std::unique_ptr<Deformation<dim>>
  Interface<dim>::deformation(const Context<dim> &context,
                              const VectorType   &u,
                              const double       *carry_time) const
  {
    (void)context;
    (void)u;
    (void)carry_time;
    return std::make_unique<Deformation<dim>>();
  }


  template <int dim>
  std::string
  Interface<dim>::inversion_advice() const
  {
    return "the material model is undefined for det F <= 0 (use "
           "'invertible neo-Hookean' or 'robust neo-Hookean' for scenes "
           "that invert elements)";
  }


  template <int dim>
  void
  Interface<dim>::solve_system(solvers::LinearSolver &,
                               VectorType &,
                               const VectorType &,
                               const bool)
  {
    AssertThrow(false,
                ExcMessage("This formulation keeps no Newton system of its "
                           "own: solve with the solid's Jacobian."));
  }


  void
  declare_parameters(ParameterHandler &prm)
  {
    const auto &registry = FormulationRegistry<3>::instance();
    prm.enter_subsection("Materials");
    prm.declare_entry("Formulation",
                      "displacement",
                      Patterns::Selection(registry.selection_pattern()),
                      "The element formulation: how a cell's displacement "
                      "becomes its energy, forces and stiffness. "
                        + registry.documentation());
    prm.leave_subsection();
    registry.declare_parameters(prm);
  }


  template <int dim>
  std::unique_ptr<Interface<dim>>
  create(const std::string &name, ParameterHandler &prm)
  {
    return FormulationRegistry<dim>::instance().create(name, prm);
  }


#define TISSUEFEM_INSTANTIATE(dim)                                          \
  template struct CellTerms<dim>;                                           \
  template class Interface<dim>;                                            \
  template void deformation_gradients(const CellCache<dim> &,               \
                                      CellTerms<dim> &);                    \
  template void check_inversion(CellTerms<dim> &);                          \
  template std::unique_ptr<Interface<dim>> create<dim>(const std::string &, \
                                                       ParameterHandler &);
  TISSUEFEM_INSTANTIATE(1)
  TISSUEFEM_INSTANTIATE(2)
  TISSUEFEM_INSTANTIATE(3)
#undef TISSUEFEM_INSTANTIATE
} // namespace tissuefem::solid::formulations
