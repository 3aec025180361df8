#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <tissuefem/base/nan_aware.h>
#include <tissuefem/materials/consistency_check.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <vector>

namespace tissuefem::materials
{
  namespace
  {
    /// A portable linear congruential generator, uniform in [-1, 1).
    class Random
    {
    public:
      double
      operator()()
      {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<double>(state >> 11) / 4503599627370496.0 - 1.0;
      }

    private:
      std::uint64_t state = 20261122;
    };

    template <int dim>
    Tensor<2, dim>
    random_tensor(Random &random, const double scale)
    {
      Tensor<2, dim> T;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          T[i][j] = scale * random();
      return T;
    }

    /// A random rotation: Q = exp of a random skew matrix, via Cayley's
    /// transform (I - W)^{-1} (I + W), which is orthogonal with det 1.
    template <int dim>
    Tensor<2, dim>
    random_rotation(Random &random)
    {
      const Tensor<2, dim> W0 = random_tensor<dim>(random, 1.);
      const Tensor<2, dim> W  = W0 - transpose(W0);
      const Tensor<2, dim> I  = unit_symmetric_tensor<dim>();
      return invert(I - W) * (I + W);
    }

    template <int dim>
    double
    max_abs(const Tensor<2, dim> &T)
    {
      double m = 0;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          m = max_keeping_nan(m, std::abs(T[i][j]));
      return m;
    }
  } // namespace


  bool
  ConsistencyReport::passes() const
  {
    return zero_stress_at_identity < 1e-10 && stress_vs_energy < 1e-6
           && tangent_vs_stress < 1e-6 && method_spread < 1e-10
           && major_asymmetry < 1e-10 && energy_taylor_slope > 1.9
           && energy_taylor_slope < 2.1 && stress_taylor_slope > 1.9
           && stress_taylor_slope < 2.1 && frame_indifference < 1e-10;
  }


  namespace
  {
    /// A sampled deformation gradient F with the fibre direction, the
    /// material's stress P and tangent A there (automatic differentiation),
    /// and the stress scale the errors at this sample are relative to.
    template <int dim>
    struct Sample
    {
      Tensor<2, dim> F, P;
      Tensor<1, dim> fibre;
      Tensor<4, dim> A;
      double         scale;
    };

    /// P against central differences of the energy, A against central
    /// differences of P (step 1e-6 in every entry of F).
    template <int dim>
    void
    compare_with_differences(const Interface<dim> &material,
                             const Sample<dim>    &s,
                             ConsistencyReport    &report)
    {
      const double h = 1e-6;
      for (unsigned int k = 0; k < dim; ++k)
        for (unsigned int l = 0; l < dim; ++l)
          {
            Tensor<2, dim> Fp = s.F, Fm = s.F;
            Fp[k][l] += h;
            Fm[k][l] -= h;
            const double dpsi = (material.energy_density(Fp, s.fibre)
                                 - material.energy_density(Fm, s.fibre))
                                / (2 * h);
            report.stress_vs_energy
              = max_keeping_nan(report.stress_vs_energy,
                                std::abs(dpsi - s.P[k][l]) / s.scale);
            const Tensor<2, dim> dP
              = (material.stress(Fp, s.fibre) - material.stress(Fm, s.fibre))
                / (2 * h);
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                report.tangent_vs_stress
                  = max_keeping_nan(report.tangent_vs_stress,
                                    std::abs(dP[i][j] - s.A[i][j][k][l])
                                      / s.scale);
          }
    }

    /// A model's own simplex stiffness (Interface::simplex_stiffness())
    /// against the AD tangent contracted with the simplex's gradients:
    /// the reference simplex's, mapped by F (nothing drawn from the random
    /// source, so that the other checks' draws stay as they were).
    template <int dim>
    void
    compare_simplex_stiffness(const Interface<dim> &material,
                              const Sample<dim>    &s,
                              ConsistencyReport    &report)
    {
      std::array<Tensor<1, dim>, dim + 1> g;
      for (unsigned int d = 0; d < dim; ++d)
        {
          g[0][d]     = -1;
          g[d + 1][d] = 1;
        }
      for (auto &gradient : g)
        gradient = s.F * gradient;
      Tensor<2, dim>      P;
      std::vector<double> K((dim + 1) * (dim + 2) / 2 * dim * dim);
      material.simplex_stiffness(s.F, s.fibre, g.data(), P, K.data());
      report.method_spread
        = max_keeping_nan(report.method_spread, max_abs(P - s.P) / s.scale);
      std::vector<double> exact(K.size());
      contract_simplex_blocks(s.A, g.data(), exact.data());
      double scale = 0;
      for (const auto &gradient : g)
        scale = std::max(scale, gradient.norm_square());
      for (unsigned int e = 0; e < K.size(); ++e)
        report.method_spread
          = max_keeping_nan(report.method_spread,
                            std::abs(K[e] - exact[e]) / (s.scale * scale));
    }


    /// The spread of stress and tangent over the tangent @p methods, and
    /// the tangent's major asymmetry.
    template <int dim>
    void
    compare_methods(const Interface<dim>             &material,
                    const Sample<dim>                &s,
                    const std::vector<TangentMethod> &methods,
                    ConsistencyReport                &report)
    {
      for (const auto method : methods)
        {
          Tensor<2, dim> P2;
          Tensor<4, dim> A2;
          material.stress_and_tangent(s.F, s.fibre, P2, A2, method);
          report.method_spread = max_keeping_nan(report.method_spread,
                                                 max_abs(P2 - s.P) / s.scale);
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = 0; j < dim; ++j)
              for (unsigned int k = 0; k < dim; ++k)
                for (unsigned int l = 0; l < dim; ++l)
                  {
                    report.method_spread = max_keeping_nan(
                      report.method_spread,
                      std::abs(A2[i][j][k][l] - s.A[i][j][k][l]) / s.scale);
                    report.major_asymmetry = max_keeping_nan(
                      report.major_asymmetry,
                      std::abs(s.A[i][j][k][l] - s.A[k][l][i][j]) / s.scale);
                  }
        }
      if (material.has_simplex_stiffness())
        compare_simplex_stiffness(material, s, report);
    }

    /// The slopes of the Taylor remainders of energy and stress at steps
    /// 1e-3 and 5e-4 along @p dF (2 if P and A are right); @p psi is the
    /// energy at F.
    template <int dim>
    void
    taylor_slopes(const Interface<dim> &material,
                  const Sample<dim>    &s,
                  const Tensor<2, dim> &dF,
                  const double          psi,
                  ConsistencyReport    &report)
    {
      auto remainders
        = [&](const double t, double &r_energy, double &r_stress) {
            const Tensor<2, dim> Ft = s.F + t * dF;
            r_energy = std::abs(material.energy_density(Ft, s.fibre) - psi
                                - t * scalar_product(s.P, dF));
            r_stress = max_abs(material.stress(Ft, s.fibre) - s.P
                               - t * double_contract<2, 0, 3, 1>(s.A, dF));
          };
      double e1, s1, e2, s2;
      remainders(1e-3, e1, s1);
      remainders(5e-4, e2, s2);
      // A remainder at round-off level (a quadratic energy's stress is
      // linear) has no meaningful slope; count it as exact.
      const double e_slope = e1 < 1e-13 * s.scale ? 2. : std::log2(e1 / e2);
      const double s_slope = s1 < 1e-13 * s.scale ? 2. : std::log2(s1 / s2);
      report.energy_taylor_slope
        = std::min(report.energy_taylor_slope, e_slope);
      report.stress_taylor_slope
        = std::min(report.stress_taylor_slope, s_slope);
    }

    /// Energy and stress under the rotation @p Q: Psi(QF) = Psi(F) and
    /// P(QF) = Q P(F) for a frame-indifferent model.
    template <int dim>
    void
    check_frame_indifference(const Interface<dim> &material,
                             const Sample<dim>    &s,
                             const Tensor<2, dim> &Q,
                             const double          psi,
                             const double          stress_scale,
                             ConsistencyReport    &report)
    {
      const double d_energy
        = std::abs(material.energy_density(Q * s.F, s.fibre) - psi)
          / std::max(std::abs(psi), stress_scale);
      const double d_stress
        = max_abs(material.stress(Q * s.F, s.fibre) - Q * s.P) / s.scale;
      report.frame_indifference
        = max_keeping_nan({report.frame_indifference, d_energy, d_stress});
    }
  } // namespace


  template <int dim>
  ConsistencyReport
  check_consistency(const std::string    &name,
                    const Interface<dim> &material,
                    const double          stress_scale)
  {
    Random            random;
    ConsistencyReport report{};
    report.model            = name;
    report.dim              = dim;
    report.inverted_samples = material.admits_inversion();

    Tensor<1, dim> fibre;
    for (unsigned int d = 0; d < dim; ++d)
      fibre[d] = d + 1.;
    fibre /= fibre.norm();

    const Tensor<2, dim> I = unit_symmetric_tensor<dim>();
    report.zero_stress_at_identity
      = max_abs(material.stress(I, fibre)) / stress_scale;

    std::vector<TangentMethod> methods
      = {TangentMethod::automatic_differentiation,
         TangentMethod::automatic_differentiation_in_F,
         TangentMethod::dealii_ad_helper};
    if (material.has_hand_coded_tangent())
      methods.push_back(TangentMethod::hand_coded);

    report.energy_taylor_slope = report.stress_taylor_slope = 10;
    // The random draws come in a fixed order (F, the Taylor direction,
    // the rotation), so that the report is reproducible.
    for (unsigned int sample = 0; sample < 20; ++sample)
      {
        Sample<dim> s;
        s.F = I + random_tensor<dim>(random, 0.3);
        if (material.admits_inversion() && sample % 2 == 1)
          s.F[0] *= -1.;
        s.fibre = fibre;
        material.stress_and_tangent(
          s.F, fibre, s.P, s.A, TangentMethod::automatic_differentiation);
        s.scale = std::max(max_abs(s.P), stress_scale);

        compare_with_differences(material, s, report);
        compare_methods(material, s, methods, report);
        const Tensor<2, dim> dF  = random_tensor<dim>(random, 1.);
        const double         psi = material.energy_density(s.F, fibre);
        taylor_slopes(material, s, dF, psi, report);
        if (material.frame_indifferent())
          check_frame_indifference(material,
                                   s,
                                   random_rotation<dim>(random),
                                   psi,
                                   stress_scale,
                                   report);
        else
          report.frame_indifference = -1;
      }
    return report;
  }


  void
  print_consistency_table(std::ostream                         &out,
                          const std::vector<ConsistencyReport> &reports)
  {
    out << std::left << std::setw(52) << "model" << std::right << std::setw(4)
        << "dim" << std::setw(10) << "P(I)" << std::setw(10) << "P-FD"
        << std::setw(10) << "A-FD" << std::setw(10) << "methods"
        << std::setw(10) << "A-A^T" << std::setw(8) << "slopeW" << std::setw(8)
        << "slopeP" << std::setw(10) << "QF" << std::setw(6) << "J<0"
        << std::setw(6) << "ok"
        << "\n";
    for (const auto &r : reports)
      {
        out << std::left << std::setw(52) << r.model << std::right
            << std::setw(4) << r.dim << std::scientific << std::setprecision(1)
            << std::setw(10) << r.zero_stress_at_identity << std::setw(10)
            << r.stress_vs_energy << std::setw(10) << r.tangent_vs_stress
            << std::setw(10) << r.method_spread << std::setw(10)
            << r.major_asymmetry << std::fixed << std::setprecision(2)
            << std::setw(8) << r.energy_taylor_slope << std::setw(8)
            << r.stress_taylor_slope;
        if (r.frame_indifference < 0)
          out << std::setw(10) << "n/a";
        else
          out << std::scientific << std::setprecision(1) << std::setw(10)
              << r.frame_indifference;
        out << std::setw(6) << (r.inverted_samples ? "yes" : "no")
            << std::setw(6) << (r.passes() ? "yes" : "NO") << "\n";
      }
    out << std::defaultfloat
        << "Columns: relative errors of P(I); of P against central differences "
           "of Psi; of A = dP/dF against central differences of P; largest "
           "difference between tangent methods; of A against its major "
           "transpose; Taylor slopes of the energy and stress remainders "
           "(2 when the derivatives are right); of Psi(QF) and P(QF) against "
           "Psi(F) and Q P(F) for random rotations Q (n/a: not frame "
           "indifferent by design); whether inverted F (det F < 0) were "
           "sampled.\n";
  }

  template ConsistencyReport
  check_consistency<1>(const std::string &, const Interface<1> &, double);
  template ConsistencyReport
  check_consistency<2>(const std::string &, const Interface<2> &, double);
  template ConsistencyReport
  check_consistency<3>(const std::string &, const Interface<3> &, double);
} // namespace tissuefem::materials
