#include <tissuefem/materials/linear_elastic.h>

namespace tissuefem::materials
{
  template class LinearElastic<1>;
  template class LinearElastic<2>;
  template class LinearElastic<3>;

  TISSUEFEM_REGISTER_MATERIAL(
    LinearElastic,
    "linear elastic",
    "small-strain linear elasticity, Psi = mu eps:eps + lambda/2 (tr eps)^2 "
    "(Jeffrey eq 4); not rotation invariant, valid for small rotations only.")
} // namespace tissuefem::materials
