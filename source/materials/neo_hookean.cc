#include <tissuefem/materials/kinematics.h>
#include <tissuefem/materials/neo_hookean.h>

namespace tissuefem::materials
{


  template <int dim, typename Volume>
  NeoHookeanFamily<dim, Volume>::NeoHookeanFamily(
    const ElasticConstants &constants,
    const ParameterHandler &)
      : lambda(constants.lambda)
      , mu(constants.mu)
  {
  }


  template <int dim, typename Volume>
  void
  NeoHookeanFamily<dim, Volume>::hand_coded_stress_and_tangent(
    const Tensor<2, dim> &F,
    const Tensor<1, dim> &,
    Tensor<2, dim> &P,
    Tensor<4, dim> &A) const
  {
    const double         J   = determinant(F);
    const double         g   = Volume::value(J);
    const double         dg  = Volume::first_derivative(J);
    const double         d2g = Volume::second_derivative(J);
    const Tensor<2, dim> cof = cofactor(F);
    const double         c1  = lambda * dg * dg + (lambda * g - mu) * d2g;
    const double         c2  = (lambda * g - mu) * dg;

    P = mu * F + c2 * cof;
    A = c1 * outer_product(cof, cof);
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        A[i][j][i][j] += mu;
    add_cofactor_derivative(F, c2, A);
  }

  template class NeoHookeanFamily<1, LogVolume>;
  template class NeoHookeanFamily<2, LogVolume>;
  template class NeoHookeanFamily<3, LogVolume>;
  template class NeoHookeanFamily<1, CubicVolume>;
  template class NeoHookeanFamily<2, CubicVolume>;
  template class NeoHookeanFamily<3, CubicVolume>;

  TISSUEFEM_REGISTER_MATERIAL(
    NeoHookean,
    "neo-Hookean",
    "compressible neo-Hookean, Psi = mu/2 (tr F^T F - d) - mu log J + "
    "lambda/2 log^2 J (Teran eq 2.8a); undefined for det F <= 0.")
  TISSUEFEM_REGISTER_MATERIAL(
    RobustNeoHookean,
    "robust neo-Hookean",
    "inversion-robust neo-Hookean: log J replaced by its cubic Taylor "
    "expansion r(J) about J = 1 (Teran eq 2.9); defined for every F.")

} // namespace tissuefem::materials
