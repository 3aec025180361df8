#include <tissuefem/contact/pose.h>

#include <cmath>

namespace tissuefem::contact
{
  template <int dim>
  Tensor<2, dim>
  rotation_matrix(const std::array<double, 3> &angles)
  {
    Tensor<2, dim> R = unit_symmetric_tensor<dim>();
    if constexpr (dim == 2)
      {
        const double c = std::cos(angles[0]), s = std::sin(angles[0]);
        R[0][0] = c;
        R[0][1] = -s;
        R[1][0] = s;
        R[1][1] = c;
      }
    else if constexpr (dim == 3)
      {
        // Rodrigues: R = I + sin(a) K + (1 - cos(a)) K^2, K the cross
        // product with the unit axis, a the vector's length.
        Tensor<1, 3> axis({angles[0], angles[1], angles[2]});
        const double angle = axis.norm();
        if (angle == 0)
          return R;
        axis /= angle;
        Tensor<2, 3> K;
        K[0][1] = -axis[2];
        K[0][2] = axis[1];
        K[1][0] = axis[2];
        K[1][2] = -axis[0];
        K[2][0] = -axis[1];
        K[2][1] = axis[0];
        R += std::sin(angle) * K + (1 - std::cos(angle)) * (K * K);
      }
    return R;
  }


  template Tensor<2, 1>
  rotation_matrix<1>(const std::array<double, 3> &);
  template Tensor<2, 2>
  rotation_matrix<2>(const std::array<double, 3> &);
  template Tensor<2, 3>
  rotation_matrix<3>(const std::array<double, 3> &);
} // namespace tissuefem::contact
