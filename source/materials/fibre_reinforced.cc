#include <tissuefem/base/input_error.h>
#include <tissuefem/materials/fibre_reinforced.h>

namespace tissuefem::materials
{
  namespace
  {
    const std::string subsection = "Fibre-reinforced robust neo-Hookean";
  }


  template <int dim>
  void
  FibreReinforced<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection(subsection);
    prm.declare_entry("Fibre law",
                      "exponential",
                      Patterns::Selection("quadratic|exponential"),
                      "'quadratic': k1/4 (I4 - 1)^2; 'exponential': "
                      "k1/(2 k2) (exp(k2 (I4 - 1)^2) - 1) for I4 > 1 only.");
    prm.declare_entry("Fibre stiffness k1",
                      "1000",
                      Patterns::Double(),
                      "k1 >= 0 (stress units).");
    prm.declare_entry("Fibre exponent k2",
                      "1",
                      Patterns::Double(),
                      "k2 > 0 (dimensionless), for the exponential law (read "
                      "but unused by the quadratic law).");
    prm.leave_subsection();
  }


  template <int dim>
  FibreReinforced<dim>::FibreReinforced(const ElasticConstants &constants,
                                        const ParameterHandler &prm)
      : matrix(constants, prm)
  {
    const std::vector<std::string> path = {"Materials", subsection};
    exponential_law        = prm.get(path, "Fibre law") == "exponential";
    k1                     = prm.get_double(path, "Fibre stiffness k1");
    k2                     = prm.get_double(path, "Fibre exponent k2");
    const std::string name = "Materials/" + subsection + "/";
    require(k1 >= 0, name + "Fibre stiffness k1", "must be >= 0");
    require(k2 > 0, name + "Fibre exponent k2", "must be > 0");
  }

  template class FibreReinforced<1>;
  template class FibreReinforced<2>;
  template class FibreReinforced<3>;

  TISSUEFEM_REGISTER_MATERIAL(
    FibreReinforced,
    "fibre-reinforced robust neo-Hookean",
    "robust neo-Hookean plus Psi_fibre(a.F^T F a) along the fibre a, "
    "quadratic or exponential (tension-only) law; defined through inversion.")
} // namespace tissuefem::materials
