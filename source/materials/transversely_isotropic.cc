#include <tissuefem/base/input_error.h>
#include <tissuefem/materials/transversely_isotropic.h>

namespace tissuefem::materials
{
  namespace
  {
    const std::string subsection = "Transversely isotropic St Venant-Kirchhoff";
  }


  template <int dim>
  void
  TransverselyIsotropic<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection(subsection);
    prm.declare_entry("Young's modulus along fibre",
                      "7500",
                      Patterns::Double(),
                      "E^L > 0 along the fibre direction (stress units). The "
                      "Materials subsection's constants hold across the "
                      "fibre. Jeffrey's muscle: 150 kPa along, 20 kPa across.");
    prm.declare_entry("Poisson's ratio along fibre",
                      "0.4",
                      Patterns::Double(),
                      "nu^L along the fibre direction, -1 < nu^L < 0.5.");
    prm.leave_subsection();
  }


  template <int dim>
  TransverselyIsotropic<dim>::TransverselyIsotropic(
    const ElasticConstants &constants,
    const ParameterHandler &prm)
      : lambda(constants.lambda)
      , mu(constants.mu)
  {
    const std::vector<std::string> path = {"Materials", subsection};
    const double E_L  = prm.get_double(path, "Young's modulus along fibre");
    const double nu_L = prm.get_double(path, "Poisson's ratio along fibre");
    const std::string name = "Materials/" + subsection + "/";
    require(E_L > 0, name + "Young's modulus along fibre", "must be > 0");
    require(nu_L > -1 && nu_L < 0.5,
            name + "Poisson's ratio along fibre",
            "must satisfy -1 < nu < 0.5");
    const ElasticConstants along
      = ElasticConstants::from_young_poisson(E_L, nu_L);
    fibre_coefficient = 0.5 * (along.lambda - lambda) + (along.mu - mu);
  }

  template class TransverselyIsotropic<1>;
  template class TransverselyIsotropic<2>;
  template class TransverselyIsotropic<3>;

  TISSUEFEM_REGISTER_MATERIAL(
    TransverselyIsotropic,
    "transversely isotropic St Venant-Kirchhoff",
    "St Venant-Kirchhoff plus (Delta lambda/2 + Delta mu)(a.E a)^2 along the "
    "fibre a (Picinbono, Jeffrey eqs 16-18, 24).")
} // namespace tissuefem::materials
