#include <tissuefem/materials/corotational.h>

namespace tissuefem::materials
{
  template class Corotational<1>;
  template class Corotational<2>;
  template class Corotational<3>;

  TISSUEFEM_REGISTER_MATERIAL(
    Corotational,
    "corotational linear elastic",
    "mu |F - R|^2 + lambda/2 (tr R^T F - d)^2 with R the polar rotation of F, "
    "differentiated exactly (SOFA's and Vega's fast model); needs det F > 0.")
} // namespace tissuefem::materials
