#pragma once

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/base/parallel.h>
#include <tissuefem/base/registry.h>
#include <tissuefem/materials/material_set.h>
#include <tissuefem/solid/cell_cache.h>
#include <tissuefem/solid/discretization.h>
#include <tissuefem/solid/fibre_field.h>
#include <tissuefem/solid/iteration_unknowns.h>

#include <functional>
#include <memory>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace tissuefem::solvers
{
  class LinearSolver;
}

namespace tissuefem::solid
{
  template <int dim>
  class DilatationCarry;
}

/**
 * Element formulations: how a cell's displacement becomes its elastic
 * energy, forces and stiffness (the displacement element, F-bar forms,
 * Jeffrey's edge-length element). Each is one class in one file pair of
 * this folder, registered by name ('Materials/Formulation'); the solid
 * keeps one cell loop and one scatter, and asks its formulation for the
 * elastic terms of each cell (cell_terms(), add_cell_rows()), for terms
 * that couple cells beyond their own dofs (add_patch_terms()), and for
 * the effective deformation gradients of a state (energies, outputs).
 */
namespace tissuefem::solid::formulations
{
  /// What a formulation sees of the solid, fixed between mesh changes.
  template <int dim>
  struct Context
  {
    const Discretization<dim>         &discretization;
    const materials::MaterialSet<dim> &materials;
    const CellCache<dim>              &cache;
    const FibreField<dim>             &fibres;
  };


  /// A formulation's own per-thread work space (make_scratch()).
  struct Scratch
  {
    virtual ~Scratch() = default;
    virtual std::unique_ptr<Scratch>
    clone() const = 0;
  };


  /**
   * One cell of an assembly pass, as the solid's cell loop sets it up
   * (inputs) and the formulation fills it (outputs). Per thread; reused
   * from cell to cell.
   */
  template <int dim>
  struct CellTerms
  {
    CellTerms(const unsigned int n_scalar, const unsigned int n_q);
    CellTerms(const CellTerms &other);

    /// Index in the cell cache, and active cell index.
    unsigned int                     c        = 0;
    unsigned int                     index    = 0;
    const materials::Interface<dim> *material = nullptr;
    /// Whether the tangent is wanted.
    bool jacobian = false;
    /// The time of the carried cell dilatations (implicit operators of a
    /// formulation that carries them; DilatationCarry), else null.
    const double *carry_time = nullptr;
    /// The displacement at each scalar shape function of the cell.
    std::vector<Tensor<1, dim>> U;
    /// F at the points (deformation_gradients()), then the first
    /// Piola-Kirchhoff stress P and tangent A = dP/dF the formulation
    /// gives there.
    std::vector<Tensor<2, dim>> F, P;
    std::vector<Tensor<4, dim>> A;
    /// The cell's rows: residual, and Jacobian (entries j >= i only).
    Vector<double>     *rhs    = nullptr;
    FullMatrix<double> *matrix = nullptr;
    /// Smallest det F where the state is undefined for the cell (then it
    /// contributes nothing and is reported); 1 if none.
    double inverted_det = 1;
    /// The formulation's own work space (make_scratch()).
    std::unique_ptr<Scratch> own;
  };


  /// Sets cell.F to F = I + sum_k U_k (x) grad phi_k at every point.
  template <int dim>
  void
  deformation_gradients(const CellCache<dim> &cache, CellTerms<dim> &cell);

  /// Sets cell.inverted_det to the smallest det F <= 0 of cell.F, unless
  /// the cell's model represents inversion.
  template <int dim>
  void
  check_inversion(CellTerms<dim> &cell);


  /**
   * The effective deformation gradients of one state (energies, outputs):
   * the plain F for the displacement element, Fbar for the F-bar forms.
   */
  template <int dim>
  class Deformation
  {
  public:
    virtual ~Deformation() = default;

    /// Replaces the plain gradients F[0..n) of the cell (quadrature weights
    /// JxW) by the formulation's; false (F unchanged) where they are not
    /// defined, an inadmissible state.
    virtual bool
    apply(const typename DoFHandler<dim>::active_cell_iterator &cell,
          std::vector<Tensor<2, dim>>                          &F,
          const double                                         *JxW,
          const unsigned int                                    n) const
    {
      (void)cell;
      (void)F;
      (void)JxW;
      (void)n;
      return true;
    }

    /// Where the formulation adds terms of its own to the model's energy
    /// density @p psi and stress @p P at the cell's F (a pressure of its
    /// own: NodalPressure), adds them; @p P may be null.
    virtual void
    add_own_terms(const typename DoFHandler<dim>::active_cell_iterator &cell,
                  const Tensor<2, dim>                                 &F,
                  double                                               &psi,
                  Tensor<2, dim>                                       *P) const
    {
      (void)cell;
      (void)F;
      (void)psi;
      (void)P;
    }
  };


  /// The patch terms' request (add_patch_terms()).
  template <int dim>
  struct PatchRequest
  {
    const VectorType                *u             = nullptr; ///< ghosted
    bool                             jacobian      = false;
    const AffineConstraints<double> *rows          = nullptr;
    bool                             inhomogeneous = false;
    /// Where the formulation keeps its own Newton system and the lean
    /// path leaves the loads to it: the inertia w (ghosted; M w enters),
    /// the mass coefficient of the Jacobian and the gravity to add in the
    /// same cell blocks.
    bool              loads            = false;
    const VectorType *inertia          = nullptr;
    double            mass_coefficient = 0;
    /// The mass is the row-sum lumped one ('Finite element/Mass').
    bool           lumped_mass = false;
    Tensor<1, dim> gravity;
  };

  /// (active cell index, det F, centre) of a cell whose state is undefined.
  template <int dim>
  using Inverted = std::vector<std::tuple<unsigned int, double, Point<dim>>>;


  template <int dim>
  class Interface
  {
  public:
    virtual ~Interface() = default;

    /// Throws InputError naming 'Materials/Formulation' where the element
    /// of @p discretization or a model of @p materials does not suit the
    /// formulation.
    virtual void
    check(const Discretization<dim>         &discretization,
          const materials::MaterialSet<dim> &materials) const = 0;

    /// Builds what the formulation keeps per mesh; the solid calls it
    /// from setup(), after its cell cache and fibres.
    virtual void
    setup(const Context<dim> &context)
    {
      (void)context;
    }

    /// How far the lean kernel of linear simplices may serve the cells.
    enum class LeanKernel
    {
      none,  ///< not at all: the general quadrature loop
      loads, ///< inertia and loads; the elastic terms are the patches'
      all    ///< everything
    };
    virtual LeanKernel
    lean_kernel() const
    {
      return LeanKernel::none;
    }

    /// Whether the fibre direction is one per cell (its normalized mean).
    virtual bool
    fibre_per_cell() const
    {
      return false;
    }

    /// Whether F is constant in each cell (one evaluation per cell).
    virtual bool
    constant_gradient() const
    {
      return false;
    }

    virtual std::unique_ptr<Scratch>
    make_scratch(const Context<dim> &context) const
    {
      (void)context;
      return nullptr;
    }

    /**
     * The elastic terms of one cell, before its loads and inertia: true
     * where they are P and A at the points (cell.P, cell.A), which the
     * cell loop contracts with the shape gradients; false where the
     * formulation adds rows itself (here or in add_cell_rows()) or its
     * terms are the patches'. Sets cell.inverted_det where undefined.
     */
    virtual bool
    cell_terms(const Context<dim> &context, CellTerms<dim> &cell) const = 0;

    /// Rows added after the cell's point terms (couplings through a cell
    /// unknown, whole-element terms).
    virtual void
    add_cell_rows(const Context<dim> &context, CellTerms<dim> &cell) const
    {
      (void)context;
      (void)cell;
    }

    /// After an assembly pass of the general path that computed the
    /// elastic terms.
    virtual void
    assembled()
    {
    }

    /// The effective deformation gradients of the ghosted state @p u,
    /// with the carried dilatations of @p carry_time where given.
    virtual std::unique_ptr<Deformation<dim>>
    deformation(const Context<dim> &context,
                const VectorType   &u,
                const double       *carry_time) const;

    /// Why a cell's state is undefined, for the inversion report.
    virtual std::string
    inversion_advice() const;

    /// @name Terms that couple each cell with the cells around its
    /// vertices (added after the cell loop), and the Newton systems
    /// they need.
    /// @{
    virtual bool
    couples_patches() const
    {
      return false;
    }

    /**
     * Called whenever the solid lays out its Jacobian (mesh change, or a
     * change of how the caller solves): where the caller solves only
     * through solve_system() with a direct solver
     * (@p through_operators), the formulation may keep its own system;
     * with @p wide, it adds the couplings its terms need to @p sparsity.
     */
    virtual void
    build_system(const Context<dim>                &context,
                 const bool                         through_operators,
                 const bool                         wide,
                 TrilinosWrappers::SparsityPattern &sparsity)
    {
      (void)context;
      (void)through_operators;
      (void)wide;
      (void)sparsity;
    }

    /// Throws InputError where the formulation cannot solve its Newton
    /// systems as the integrator asks (@p through_operators: only through
    /// solve_system() with a direct solver); called when an integrator
    /// says how it solves, before its first step.
    virtual void
    check_solving(const bool through_operators) const
    {
      (void)through_operators;
    }

    /// Whether Jacobians go into the formulation's own system.
    virtual bool
    has_system() const
    {
      return false;
    }

    /// Whether the own system takes the inertia and gravity into its cell
    /// blocks (the lean path then leaves them to add_patch_terms()); else
    /// they come with the displacement block of finish_system().
    virtual bool
    system_takes_loads() const
    {
      return has_system();
    }

    /// The own system's matrix (its displacement rows hold the
    /// Jacobian's), null without one.
    virtual const MatrixType *
    system_matrix() const
    {
      return nullptr;
    }

    virtual void
    clear_system()
    {
    }

    /// After a Jacobian's assembly: the displacement block @p uu (null if
    /// it holds nothing) joins the own system.
    virtual void
    finish_system(const MatrixType *uu, VectorType &residual)
    {
      (void)uu;
      (void)residual;
    }

    virtual void
    solve_system(solvers::LinearSolver &solver,
                 VectorType            &x,
                 const VectorType      &b,
                 const bool             refactorize);

    virtual void
    add_patch_terms(const Context<dim>      &context,
                    const PatchRequest<dim> &request,
                    MatrixType              &jacobian,
                    VectorType              &residual,
                    Inverted<dim>           &inverted)
    {
      (void)context;
      (void)request;
      (void)jacobian;
      (void)residual;
      (void)inverted;
    }
    /// @}

    /// @name Unknowns of the formulation's own, iterated with Newton
    /// (IterationUnknowns), and cell dilatations carried across mesh
    /// changes.
    /// @{
    virtual IterationUnknowns *
    iteration_unknowns()
    {
      return nullptr;
    }

    virtual DilatationCarry<dim> *
    carry()
    {
      return nullptr;
    }
    /// @}

    /// What it holds, in bytes.
    virtual std::size_t
    memory_consumption() const
    {
      return 0;
    }
  };


  template <int dim>
  using FormulationRegistry = Registry<Interface<dim>, ParameterHandler &>;

  /// Declares 'Materials/Formulation' (its choices: what is registered)
  /// and every formulation's own parameters.
  void
  declare_parameters(ParameterHandler &prm);

  /// The formulation 'Materials/Formulation' names, reading its own
  /// parameters from @p prm, for the solid.
  template <int dim>
  std::unique_ptr<Interface<dim>>
  create(const std::string &name, ParameterHandler &prm);

  namespace internal
  {
    /// Whether @p T has a static declare_parameters(ParameterHandler &).
    template <typename T, typename = void>
    struct declares_parameters : std::false_type
    {
    };
    template <typename T>
    struct declares_parameters<T,
                               std::void_t<decltype(T::declare_parameters(
                                 std::declval<ParameterHandler &>()))>>
        : std::true_type
    {
    };

    /// A formulation reads its parameters where it has a constructor that
    /// takes them, else it has none.
    template <template <int> class Formulation, int dim>
    std::unique_ptr<Interface<dim>>
    make(ParameterHandler &prm)
    {
      if constexpr (std::is_constructible_v<Formulation<dim>,
                                            ParameterHandler &>)
        return std::make_unique<Formulation<dim>>(prm);
      else
        {
          (void)prm;
          return std::make_unique<Formulation<dim>>();
        }
    }

    template <template <int> class Formulation>
    void
    add_formulation(const std::string &name, const std::string &description)
    {
      // Parameters are declared once (by the 3D class: they do not depend
      // on the dimension).
      std::function<void(ParameterHandler &)> declarer;
      if constexpr (declares_parameters<Formulation<3>>::value)
        declarer = &Formulation<3>::declare_parameters;
      FormulationRegistry<1>::instance().add(name,
                                             description,
                                             nullptr,
                                             &make<Formulation, 1>);
      FormulationRegistry<2>::instance().add(name,
                                             description,
                                             nullptr,
                                             &make<Formulation, 2>);
      FormulationRegistry<3>::instance().add(name,
                                             description,
                                             declarer,
                                             &make<Formulation, 3>);
    }
  } // namespace internal
} // namespace tissuefem::solid::formulations

/// Registers formulation class template @p Formulation under @p name, in
/// every dimension; at namespace scope in the formulation's source file.
#define TISSUEFEM_REGISTER_FORMULATION(Formulation, name, description) \
  namespace                                                            \
  {                                                                    \
    const bool tissuefem_formulation_##Formulation = [] {              \
      ::tissuefem::solid::formulations::internal::add_formulation<     \
        Formulation>(name, description);                               \
      return true;                                                     \
    }();                                                               \
  }
