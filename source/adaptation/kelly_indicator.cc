// Kelly's indicator as a registered refinement indicator.
#include <deal.II/numerics/error_estimator.h>

#include <tissuefem/adaptation/indicator.h>
#include <tissuefem/base/parallel.h>

namespace tissuefem::adaptation
{
  /**
   * Kelly, Gago, Zienkiewicz and Babuska's indicator (deal.II's
   * KellyErrorEstimator): per cell, the jump of the displacement gradient
   * across its faces, integrated over them (length units times
   * sqrt(length^(dim-1))). It knows nothing of the material, so it weighs
   * a soft region as much as a stiff one with the same gradient jumps.
   */
  template <int dim>
  class KellyIndicator : public Indicator<dim>
  {
  public:
    void
    estimate(const solid::Solid<dim> &solid,
             const VectorType        &u_ghosted,
             const double,
             Vector<float> &indicator) const override
    {
      const auto &discretization = solid.get_discretization();
      KellyErrorEstimator<dim>::estimate(*discretization.mapping,
                                         discretization.dof_handler,
                                         discretization.face_quadrature,
                                         {},
                                         u_ghosted,
                                         indicator,
                                         ComponentMask(),
                                         nullptr,
                                         numbers::invalid_unsigned_int,
                                         Utilities::MPI::this_mpi_process(
                                           parallel_tools::communicator()));
    }
  };
} // namespace tissuefem::adaptation

namespace
{
  using tissuefem::adaptation::KellyIndicator;
}
TISSUEFEM_REGISTER_INDICATOR(
  KellyIndicator,
  "Kelly",
  "Kelly's indicator, the jump of the displacement gradient across cell "
  "faces (length units times sqrt(length^(dim-1))).")
