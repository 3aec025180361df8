#include <tissuefem/postprocess/final_state.h>
#include <tissuefem/solid/quantities.h>
#include <tissuefem/solid/self_overlap.h>

#include <iomanip>
#include <sstream>

#include <tissuefem/base/moved_entries.h>

namespace tissuefem::postprocess
{
  template <int dim>
  void
  FinalState<dim>::declare_parameters(ParameterHandler &prm)
  {
    moved_entries::declare(
      prm,
      "Output/Report rest shape",
      "Output/Final state/Report rest shape",
      "false",
      Patterns::Bool(),
      "At the end of the run, report (on screen and in the summary file) the "
      "distance from the rest shape up to a rigid motion (largest vertex "
      "distance after the best rigid fit, length units), the smallest J = "
      "det F, and the tangled share of the volume (inverted, or where the "
      "body overlaps itself: solid/self_overlap.h): the figures of an "
      "inversion-recovery test.");
  }


  template <int dim>
  FinalState<dim>::FinalState(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.enter_subsection("Final state");
    report_rest_shape = prm.get_bool("Report rest shape");
    prm.leave_subsection();
    prm.leave_subsection();
  }


  template <int dim>
  void
  FinalState<dim>::finish(const time::State &state,
                          const RunTotals &,
                          output::RunRecord &record)
  {
    auto &screen = parallel_tools::screen();
    auto &solid  = *this->context->scene.solid;
    if (report_rest_shape)
      {
        const auto &d = solid.get_discretization();
        VectorType  u;
        d.initialize_vector(u, true);
        u = state.u;
        std::ostringstream rest;
        rest << std::setprecision(4) << "distance from rest shape "
             << solid::distance_from_rest_shape(d, u) << " min J "
             << solid::min_jacobian(d, u) << " tangled "
             << solid::tangled_volume_fraction(d, u);
        this->context->summary.line(rest.str());
        screen << rest.str()
               << " (largest vertex distance after the best rigid fit, "
                  "length units; smallest det F; share of the volume that is "
                  "inverted or overlaps the body elsewhere)"
               << std::endl;
      }
    const double       stored = solid.stored_energy(state.u);
    std::ostringstream energy;
    energy << "final elastic energy " << std::setprecision(8) << stored;
    this->context->summary.line(energy.str());
    screen << energy.str() << " (energy units, int Psi dV)" << std::endl;
    record.add("stored energy", stored, "energy units, int Psi dV at the end");
    record.add("kinetic energy",
               solid.kinetic_energy(state.v),
               "energy units, 1/2 v.M v at the end");
  }

  template class FinalState<1>;
  template class FinalState<2>;
  template class FinalState<3>;

  TISSUEFEM_REGISTER_POSTPROCESSOR(
    FinalState,
    "final state",
    "the final elastic and kinetic energy, and optionally the distance from "
    "the rest shape and the smallest det F.")
} // namespace tissuefem::postprocess
