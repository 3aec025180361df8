#include <tissuefem/materials/st_venant_kirchhoff.h>

namespace tissuefem::materials
{
  template class StVenantKirchhoff<1>;
  template class StVenantKirchhoff<2>;
  template class StVenantKirchhoff<3>;

  TISSUEFEM_REGISTER_MATERIAL(
    StVenantKirchhoff,
    "St Venant-Kirchhoff",
    "Psi = mu E:E + lambda/2 (tr E)^2, E = (F^T F - I)/2 (Picinbono's "
    "non-linear model, Jeffrey eq 12).")
} // namespace tissuefem::materials
