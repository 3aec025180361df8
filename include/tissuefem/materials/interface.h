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
    hand_coded,
    /// hand_coded where the model has a closed form
    /// (Interface::has_hand_coded_tangent()), else
    /// automatic_differentiation.
    fastest
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
   * The part of a model's energy that locks as nu -> 1/2: Psi(F) =
   * Psi_rest(F) + lambda/2 g(J)^2, with Psi_rest free of lambda (Teran eq
   * 2.8a's log^2 J term). Mixed formulations (solid/formulations/
   * nodal_pressure.h) replace it by a pressure of their own. lambda = 0:
   * the model has no such part.
   */
  struct VolumetricPart
  {
    /// lambda and the shear modulus mu (stress units).
    double lambda = 0;
    double mu     = 0;
    /// g(J), g'(J), g''(J).
    double g = 0, dg = 0, d2g = 0;
  };

  /// The node blocks K_kl = sum_mn A_imjn g_k,m g_l,n, k <= l, of a
  /// tangent @p A and a simplex's dim + 1 gradients @p g, packed as
  /// Interface::simplex_stiffness() gives them.
  template <int dim>
  void
  contract_simplex_blocks(const Tensor<4, dim> &A,
                          const Tensor<1, dim> *g,
                          double               *K)
  {
    for (unsigned int k = 0, b = 0; k <= dim; ++k)
      for (unsigned int l = k; l <= dim; ++l, ++b)
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            {
              double sum = 0;
              for (unsigned int m = 0; m < dim; ++m)
                for (unsigned int n = 0; n < dim; ++n)
                  sum += A[i][m][j][n] * g[k][m] * g[l][n];
              K[(b * dim + i) * dim + j] = sum;
            }
  }


  /**
   * A hyperelastic material: an energy density Psi(F; a) per unit reference
   * volume, its first Piola-Kirchhoff stress P = dPsi/dF and the tangent
   * A = dP/dF, with A_ijkl = d P_ij / d F_kl. The unit vector a is the
   * reference fibre direction at the point; isotropic models ignore it.
   */
  template <int dim>
  class Interface
  {
  public:
    virtual ~Interface() = default;

    virtual double
    energy_density(const Tensor<2, dim> &F,
                   const Tensor<1, dim> &fibre) const = 0;

    virtual Tensor<2, dim>
    stress(const Tensor<2, dim> &F, const Tensor<1, dim> &fibre) const = 0;

    virtual void
    stress_and_tangent(const Tensor<2, dim> &F,
                       const Tensor<1, dim> &fibre,
                       Tensor<2, dim>       &P,
                       Tensor<4, dim>       &A,
                       const TangentMethod   method) const = 0;

    /// The stresses at @p n points (F[i], fibre[i]) in one call, so that
    /// element kernels make one virtual call per batch of cells; models
    /// override it with a loop the compiler can inline.
    virtual void
    stresses(const unsigned int    n,
             const Tensor<2, dim> *F,
             const Tensor<1, dim> *fibre,
             Tensor<2, dim>       *P) const
    {
      for (unsigned int i = 0; i < n; ++i)
        P[i] = stress(F[i], fibre[i]);
    }

    /// Stresses and tangents at @p n points in one call (see stresses()).
    virtual void
    stresses_and_tangents(const unsigned int    n,
                          const Tensor<2, dim> *F,
                          const Tensor<1, dim> *fibre,
                          Tensor<2, dim>       *P,
                          Tensor<4, dim>       *A,
                          const TangentMethod   method) const
    {
      for (unsigned int i = 0; i < n; ++i)
        stress_and_tangent(F[i], fibre[i], P[i], A[i], method);
    }

    /**
     * For a linear simplex (one F per cell, dim + 1 shape gradients @p g):
     * the stress P and the node blocks of the stiffness per unit volume,
     * K_kl = sum_mn A_imjn g_k,m g_l,n, for k <= l in the order (0,0),
     * (0,1), ..., (0,d), (1,1), ..., each dim x dim row-major into @p K (as
     * solid::LinearSimplexKernel packs a cell matrix). This default
     * contracts the A of stress_and_tangent() (the fastest method); models
     * whose tangent has a structure cheaper to contract than to write out
     * override it and has_simplex_stiffness().
     */
    virtual void
    simplex_stiffness(const Tensor<2, dim> &F,
                      const Tensor<1, dim> &fibre,
                      const Tensor<1, dim> *g,
                      Tensor<2, dim>       &P,
                      double               *K) const
    {
      Tensor<4, dim> A;
      stress_and_tangent(F, fibre, P, A, TangentMethod::fastest);
      contract_simplex_blocks(A, g, K);
    }

    /// Whether simplex_stiffness() is the model's own, cheaper than
    /// stress_and_tangent() and the contraction.
    virtual bool
    has_simplex_stiffness() const
    {
      return false;
    }

    /// Whether the energy depends on the fibre direction.
    virtual bool
    uses_fibres() const
    {
      return false;
    }

    /// Whether Psi(QF) = Psi(F) for rotations Q (false for small-strain
    /// linear elasticity).
    virtual bool
    frame_indifferent() const
    {
      return true;
    }

    /**
     * Whether the model is written in the right Cauchy-Green tensor C and so
     * admits the edge-length formulation of edge_length_element().
     */
    virtual bool
    has_edge_length_form() const
    {
      return false;
    }

    /**
     * Energy, nodal forces dW/dQ and stiffness d2W/dQ2 of one linear simplex
     * (dim + 1 nodes) written through its squared edge lengths (Jeffrey eqs
     * 19-31): C = -1/2 sum_{j != k} L_jk^2 alpha_j (x) alpha_k (eq 26), with
     * alpha_j the reference gradients of the barycentric coordinates, and
     * W = V Psi(C). Q holds the deformed node positions; forces and
     * stiffness are indexed node * dim + component. Differentiated by
     * automatic differentiation of W with respect to Q.
     */
    virtual void
    edge_length_element(const std::vector<Tensor<1, dim>> &alpha,
                        const double                       volume,
                        const std::vector<Tensor<1, dim>> &Q,
                        const Tensor<1, dim>              &fibre,
                        double                            &energy,
                        std::vector<double>               &forces,
                        std::vector<double>               *stiffness) const;

    /// Whether stress_and_tangent() accepts TangentMethod::hand_coded.
    virtual bool
    has_hand_coded_tangent() const
    {
      return false;
    }

    /// Whether the energy is finite for det F <= 0 (inverted elements).
    virtual bool
    admits_inversion() const = 0;

    /// The volumetric part at J = det F, where the model has one (else
    /// lambda = 0).
    virtual VolumetricPart
    volumetric_part(const double J) const
    {
      (void)J;
      return {};
    }
  };

  template <int dim>
  inline void
  Interface<dim>::edge_length_element(const std::vector<Tensor<1, dim>> &,
                                      const double,
                                      const std::vector<Tensor<1, dim>> &,
                                      const Tensor<1, dim> &,
                                      double &,
                                      std::vector<double> &,
                                      std::vector<double> *) const
  {
    throw InputError("Parameter 'Materials/Formulation': the material has no "
                     "edge-length form (it is not written in C = F^T F)");
  }

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
#define TISSUEFEM_REGISTER_MATERIAL(Model, name, description)             \
  namespace                                                               \
  {                                                                       \
    const bool tissuefem_registered_##Model                               \
      = ::tissuefem::materials::register_model<Model>(name, description); \
  }
