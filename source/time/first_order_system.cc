#include <tissuefem/base/input_error.h>
#include <tissuefem/time/first_order_system.h>
#include <tissuefem/time/nodal.h>

#include <cmath>

namespace tissuefem::time
{
  const char *const first_order_damping_documentation
    = "Mass-proportional damping gamma/m (1/s if SI), as in the damped "
      "central difference (Jeffrey eq 10).";


  void
  declare_damping_ratio(ParameterHandler &prm, const std::string &documentation)
  {
    prm.declare_entry("Damping ratio", "0", Patterns::Double(0), documentation);
  }


  double
  get_damping_ratio(const ParameterHandler &prm)
  {
    return prm.get_double("Damping ratio");
  }


  void
  check_damping_ratio(const double damping, const std::string &section)
  {
    require(std::isfinite(damping) && damping >= 0,
            section + "Damping ratio",
            "must be >= 0");
  }


  FirstOrderSystem::FirstOrderSystem(const double       damping,
                                     const std::string &integrator,
                                     const std::string &alternative)
      : c(damping)
      , integrator(integrator)
      , alternative(alternative)
  {
  }


  void
  FirstOrderSystem::reinit(solid::Operators &solid, const VectorType &like)
  {
    if (solid.has_hanging_nodes())
      throw InputError("Parameter 'Time integration/Integrator': " + integrator
                       + " uses lumped masses, which are not condensed at "
                         "hanging nodes; use it without mesh refinement");
    lumped = &solid.lumped_mass();
    for (unsigned int i = 0; i < local_size(like); ++i)
      if (!(local_entries(*lumped)[i] > 0))
        throw InputError("Parameter 'Time integration/Integrator': the "
                         "row-sum lumped mass is not positive at some "
                         "node (P2 simplices); use linear elements"
                         + alternative);
    free_mask = like;
    free_mask = 1.;
    solid.zero_constrained_entries(free_mask);
  }


  double
  FirstOrderSystem::damping_power(const VectorType &v) const
  {
    if (c == 0)
      return 0;
    const double *m = local_entries(*lumped), *vp = local_entries(v);
    double        sum = 0;
    for (unsigned int i = 0; i < local_size(v); ++i)
      sum += m[i] * vp[i] * vp[i];
    return c * Utilities::MPI::sum(sum, parallel_tools::communicator());
  }
} // namespace tissuefem::time
