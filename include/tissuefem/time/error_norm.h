#pragma once

#include <deal.II/base/parameter_handler.h>

#include <tissuefem/base/parallel.h>

#include <string>
#include <vector>

namespace tissuefem::time
{
  using namespace dealii;

  /**
   * The local error tolerances of the adaptive integrators and the norm
   * they judge an error estimate by: the root mean square, over the free
   * degrees of freedom, of e_u / (atol_u + rtol |u|) and e_v / (atol_v +
   * rtol |v|) (Hairer and Wanner's weighted norm, as RADAU5 and ARKode use
   * it). A step is accepted when the norm is at most 1.
   */
  struct ErrorTolerances
  {
    /// Declares the three tolerances in the current subsection.
    static void
    declare_parameters(ParameterHandler  &prm,
                       const std::string &relative = "1e-4",
                       const std::string &absolute = "1e-6",
                       const std::string &velocity = "1e-4");
    /// Reads them from the current subsection; @p section names it in
    /// error messages (e.g. "Time integration/Radau IIA/").
    void
    parse_parameters(const ParameterHandler &prm, const std::string &section);

    double relative = 1e-4, absolute_u = 1e-6, absolute_v = 1e-4;

    /**
     * The weighted RMS norm of the displacement parts @p xu and velocity
     * parts @p xv (all laid out like the unknowns), scaled with the larger
     * of |y0| and |y1| (y1 optional) entry by entry; only entries where
     * @p free is positive count. Collective over the processes.
     */
    double
    norm(const std::vector<const VectorType *> &xu,
         const std::vector<const VectorType *> &xv,
         const VectorType                      &free,
         const VectorType                      &u0,
         const VectorType                      &v0,
         const VectorType                      *u1 = nullptr,
         const VectorType                      *v1 = nullptr) const;
  };
} // namespace tissuefem::time
