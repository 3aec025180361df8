#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <tissuefem/base/registry.h>

#include <memory>
#include <string>

namespace tissuefem::materials
{
  using namespace dealii;

  /// How the tangent dP/dF (and the stress with it) is computed.
  enum class TangentMethod
  {
    /// Exact derivatives of the energy by fixed-size Sacado numbers: of
    /// Psi(I1, J) for models written in invariants, else of Psi(F).
    automatic_differentiation,
    /// Nested fixed-size Sacado numbers SFad<SFad<double,d*d>,d*d> seeded
    /// with the entries of F, for every model.
    automatic_differentiation_in_F,
    /// deal.II's Differentiation::AD::ScalarFunction with dynamic Sacado
    /// numbers, the approach of deal.II's step-71. Kept for comparison.
    dealii_ad_helper,
    /// Closed-form stress and tangent, where a material provides them.
    hand_coded
  };

  /// The names of the tangent methods, separated by '|'.
  std::string
  tangent_method_pattern();

  TangentMethod
  parse_tangent_method(const std::string &name);

  /**
   * The isotropic elastic constants every model is given, in the units of
   * stress (Pa if SI).
   */
  struct ElasticConstants
  {
    double lambda;
    double mu;

    /// From Young's modulus E > 0 and Poisson's ratio -1 < nu < 0.5.
    static ElasticConstants
    from_young_poisson(const double E, const double nu);
  };

  /**
   * A hyperelastic material: an energy density Psi(F) per unit reference
   * volume, its first Piola-Kirchhoff stress P = dPsi/dF and the tangent
   * A = dP/dF, with A_ijkl = d P_ij / d F_kl.
   */
  template <int dim>
  class Interface
  {
  public:
    virtual ~Interface() = default;

    virtual double
    energy_density(const Tensor<2, dim> &F) const = 0;

    virtual Tensor<2, dim>
    stress(const Tensor<2, dim> &F) const = 0;

    virtual void
    stress_and_tangent(const Tensor<2, dim> &F,
                       Tensor<2, dim>       &P,
                       Tensor<4, dim>       &A,
                       const TangentMethod   method) const = 0;

    /// Whether stress_and_tangent() accepts TangentMethod::hand_coded.
    virtual bool
    has_hand_coded_tangent() const
    {
      return false;
    }

    /// Whether the energy is finite for det F <= 0 (inverted elements).
    virtual bool
    admits_inversion() const = 0;
  };

  /// The table of materials: name -> factory from the elastic constants and
  /// the parameter handler (for a model's own subsection).
  template <int dim>
  using MaterialRegistry = Registry<Interface<dim>,
                                    const ElasticConstants &,
                                    const ParameterHandler &>;

  /**
   * Adds @p Model (templated on dim) under @p name for dim = 1, 2, 3.
   * @p Model<dim> must be constructible from (ElasticConstants,
   * ParameterHandler) and have a static declare_parameters(ParameterHandler&).
   */
  template <template <int> class Model>
  bool
  register_model(const std::string &name, const std::string &description)
  {
    auto add = [&](auto &registry, auto dim_tag) {
      constexpr int dim = decltype(dim_tag)::value;
      registry.add(name,
                   description,
                   &Model<dim>::declare_parameters,
                   [](const ElasticConstants &constants,
                      const ParameterHandler &prm) {
                     return std::unique_ptr<Interface<dim>>(
                       std::make_unique<Model<dim>>(constants, prm));
                   });
    };
    add(MaterialRegistry<1>::instance(), std::integral_constant<int, 1>());
    add(MaterialRegistry<2>::instance(), std::integral_constant<int, 2>());
    add(MaterialRegistry<3>::instance(), std::integral_constant<int, 3>());
    return true;
  }
} // namespace tissuefem::materials

/// Registers a material model at the end of its source file.
#define TISSUEFEM_REGISTER_MATERIAL(Model, name, description)            \
  namespace                                                              \
  {                                                                      \
    const bool tissuefem_registered_##Model =                            \
      ::tissuefem::materials::register_model<Model>(name, description);  \
  }
