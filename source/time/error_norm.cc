#include <tissuefem/base/input_error.h>
#include <tissuefem/time/error_norm.h>
#include <tissuefem/time/nodal.h>

#include <cmath>

namespace tissuefem::time
{
  void
  ErrorTolerances::declare_parameters(ParameterHandler  &prm,
                                      const std::string &relative,
                                      const std::string &absolute,
                                      const std::string &velocity)
  {
    prm.declare_entry("Relative tolerance",
                      relative,
                      Patterns::Double(0),
                      "Local error tolerance per step relative to |u|, |v| "
                      "(dimensionless); in (0, 1).");
    prm.declare_entry("Absolute tolerance",
                      absolute,
                      Patterns::Double(0),
                      "Local error tolerance per step for displacements "
                      "(length units); > 0.");
    prm.declare_entry("Absolute velocity tolerance",
                      velocity,
                      Patterns::Double(0),
                      "Local error tolerance per step for velocities (length "
                      "per time unit); > 0.");
  }


  void
  ErrorTolerances::parse_parameters(const ParameterHandler &prm,
                                    const std::string      &section)
  {
    relative   = prm.get_double("Relative tolerance");
    absolute_u = prm.get_double("Absolute tolerance");
    absolute_v = prm.get_double("Absolute velocity tolerance");
    require(std::isfinite(relative) && relative > 0 && relative < 1,
            section + "Relative tolerance",
            "must lie in (0, 1)");
    require(std::isfinite(absolute_u) && absolute_u > 0,
            section + "Absolute tolerance",
            "must be > 0");
    require(std::isfinite(absolute_v) && absolute_v > 0,
            section + "Absolute velocity tolerance",
            "must be > 0");
  }


  double
  ErrorTolerances::norm(const std::vector<const VectorType *> &xu,
                        const std::vector<const VectorType *> &xv,
                        const VectorType                      &free,
                        const VectorType                      &u0,
                        const VectorType                      &v0,
                        const VectorType                      *u1,
                        const VectorType                      *v1) const
  {
    const double *is_free = local_entries(free);
    const double *a0 = local_entries(u0), *b0 = local_entries(v0);
    const double *a1  = u1 ? local_entries(*u1) : nullptr;
    const double *b1  = v1 ? local_entries(*v1) : nullptr;
    double        sum = 0, count = 0;
    for (unsigned int i = 0; i < local_size(free); ++i)
      if (is_free[i] > 0)
        {
          double su = std::abs(a0[i]), sv = std::abs(b0[i]);
          if (a1)
            su = std::max(su, std::abs(a1[i]));
          if (b1)
            sv = std::max(sv, std::abs(b1[i]));
          su = absolute_u + relative * su;
          sv = absolute_v + relative * sv;
          for (const auto *x : xu)
            sum += std::pow(local_entries(*x)[i] / su, 2);
          for (const auto *x : xv)
            sum += std::pow(local_entries(*x)[i] / sv, 2);
          count += xu.size() + xv.size();
        }
    sum   = Utilities::MPI::sum(sum, parallel_tools::communicator());
    count = Utilities::MPI::sum(count, parallel_tools::communicator());
    return count > 0 ? std::sqrt(sum / count) : 0.;
  }
} // namespace tissuefem::time
