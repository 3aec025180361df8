#include <tissuefem/materials/tangent_projection.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace tissuefem::materials
{
  template <int dim>
  unsigned int
  project_to_positive_definite(Tensor<4, dim> &A)
  {
    constexpr unsigned int               n = dim * dim;
    std::array<std::array<double, n>, n> M, V;
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int b = 0; b < n; ++b)
        {
          // Symmetrized against round-off in A.
          M[a][b] = 0.5
                    * (A[a / dim][a % dim][b / dim][b % dim]
                       + A[b / dim][b % dim][a / dim][a % dim]);
          V[a][b] = a == b ? 1. : 0.;
        }
    double norm = 0;
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int b = 0; b < n; ++b)
        norm += M[a][b] * M[a][b];
    if (norm == 0)
      return 0;
    for (unsigned int sweep = 0; sweep < 50; ++sweep)
      {
        double off = 0;
        for (unsigned int a = 0; a < n; ++a)
          for (unsigned int b = a + 1; b < n; ++b)
            off += M[a][b] * M[a][b];
        if (off <= 1e-30 * norm)
          break;
        for (unsigned int p = 0; p < n; ++p)
          for (unsigned int q = p + 1; q < n; ++q)
            {
              if (std::abs(M[p][q]) < 1e-300)
                continue;
              // The rotation in the (p, q) plane that zeroes M_pq.
              const double theta = (M[q][q] - M[p][p]) / (2 * M[p][q]);
              const double t
                = (theta >= 0 ? 1. : -1.)
                  / (std::abs(theta) + std::sqrt(theta * theta + 1));
              const double c = 1 / std::sqrt(t * t + 1), s = t * c;
              for (unsigned int k = 0; k < n; ++k)
                {
                  const double mkp = M[k][p], mkq = M[k][q];
                  M[k][p] = c * mkp - s * mkq;
                  M[k][q] = s * mkp + c * mkq;
                }
              for (unsigned int k = 0; k < n; ++k)
                {
                  const double mpk = M[p][k], mqk = M[q][k];
                  M[p][k] = c * mpk - s * mqk;
                  M[q][k] = s * mpk + c * mqk;
                }
              for (unsigned int k = 0; k < n; ++k)
                {
                  const double vkp = V[k][p], vkq = V[k][q];
                  V[k][p] = c * vkp - s * vkq;
                  V[k][q] = s * vkp + c * vkq;
                }
            }
      }
    double largest = 0;
    for (unsigned int a = 0; a < n; ++a)
      largest = std::max(largest, std::abs(M[a][a]));
    const double floor  = 1e-6 * largest;
    unsigned int raised = 0;
    for (unsigned int a = 0; a < n; ++a)
      if (M[a][a] < floor)
        ++raised;
    if (raised == 0)
      return 0;
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int b = 0; b < n; ++b)
        {
          double value = 0;
          for (unsigned int k = 0; k < n; ++k)
            value += V[a][k] * std::max(M[k][k], floor) * V[b][k];
          A[a / dim][a % dim][b / dim][b % dim] = value;
        }
    return raised;
  }

  template unsigned int
  project_to_positive_definite<1>(Tensor<4, 1> &);
  template unsigned int
  project_to_positive_definite<2>(Tensor<4, 2> &);
  template unsigned int
  project_to_positive_definite<3>(Tensor<4, 3> &);
} // namespace tissuefem::materials
