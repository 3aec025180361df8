#pragma once

#include <deal.II/base/tensor.h>

#include <tissuefem/materials/interface.h>

#include <ostream>
#include <string>
#include <vector>

namespace tissuefem::materials
{
  /**
   * The results of checking one material against its own energy at random
   * deformation gradients (inverted ones too where the model admits them).
   * Errors are relative to max(|P|, mu-like scale); slopes are the smallest
   * observed log2(r(h) / r(h/2)) of Taylor remainders, 2 when the derivative
   * is right.
   */
  struct ConsistencyReport
  {
    std::string model;
    int         dim;
    double      zero_stress_at_identity;
    double      stress_vs_energy;
    double      tangent_vs_stress;
    /// The largest difference between tangent methods (and, for models
    /// with their own simplex stiffness, between it and the AD tangent
    /// contracted with a simplex's gradients).
    double method_spread;
    double major_asymmetry;
    double energy_taylor_slope;
    double stress_taylor_slope;
    /// max |Psi(QF) - Psi(F)| and |P(QF) - Q P(F)| over random rotations Q;
    /// negative when the model is not meant to be frame indifferent.
    double frame_indifference;
    bool   inverted_samples;

    /// Whether every figure is within the tolerances of passes().
    bool
    passes() const;
  };

  /// Runs the checks on @p material with a fixed random seed.
  template <int dim>
  ConsistencyReport
  check_consistency(const std::string    &name,
                    const Interface<dim> &material,
                    const double          stress_scale);

  /// Prints reports as an aligned table with a header.
  void
  print_consistency_table(std::ostream                         &out,
                          const std::vector<ConsistencyReport> &reports);
} // namespace tissuefem::materials
