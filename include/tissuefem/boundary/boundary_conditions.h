#pragma once

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/fe/component_mask.h>
#include <deal.II/grid/tria.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace tissuefem::boundary
{
  using namespace dealii;

  /**
   * The 'Boundary conditions' subsection: prescribed displacements and
   * tractions by boundary id, body forces and initial state, all as muparser
   * expressions of the reference position (x, y, z) and time t.
   */
  struct BoundaryParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /// Replaces 'Load factor = automatic' by what it means for this run:
    /// 't / (@p end_time)' if @p quasistatic (without a manufactured
    /// solution) and no load expression names t itself, '1' otherwise.
    void
    resolve_load_factor(const bool quasistatic, const std::string &end_time);

    std::string dirichlet, neumann, body_force, gravity, initial_displacement,
      initial_velocity, load_factor;
    /// Why 'Load factor = automatic' became what it is (empty if the file
    /// gave a factor); see resolve_load_factor().
    std::string load_factor_note;
  };

  template <int dim>
  class BoundaryConditions
  {
  public:
    /// Parses every expression for @p dim; throws InputError naming the
    /// parameter on malformed input.
    explicit BoundaryConditions(const BoundaryParameters &parameters);

    struct Dirichlet
    {
      types::boundary_id             id;
      ComponentMask                  mask;
      std::unique_ptr<Function<dim>> displacement;
      /// False if the expressions do not name the time t: the values are
      /// then computed once per mesh, not every step.
      bool time_dependent = true;
    };
    struct Neumann
    {
      types::boundary_id             id;
      std::unique_ptr<Function<dim>> traction;
    };

    /// Sets the time at which all expressions are evaluated, and the load
    /// factor to load_factor_in_force(time).
    void
    set_time(const double time);

    /// lambda(@p time) of 'Load factor' (dimensionless).
    double
    load_factor_at(const double time) const;

    /// The factor the loads carry at @p time: the held one during a load
    /// continuation (held_load_factor), else lambda(@p time).
    double
    load_factor_in_force(const double time) const;

    /// 'Load factor' as given, or as 'automatic' resolved it, for the
    /// run's first lines ("lambda(t) = t / (2) (automatic: ...)").
    std::string
    describe_load_factor() const;

    /// Whether 'Load factor' names t (else it is a constant).
    bool
    load_factor_names_time() const;

    /// Whether a Neumann, body force or load factor expression names t.
    bool
    loads_name_time() const
    {
      return loads_name_time_;
    }

    /// Whether there is any load: gravity, a body force or a traction.
    bool
    has_loads() const;

    /**
     * Whether anything the solid is given changes with time: a Dirichlet,
     * Neumann or body force expression, or (where there are loads) the
     * load factor, names t. If
     * not, a quasistatic problem is the same at every time, and a smaller
     * step cannot help a failed one.
     */
    bool
    changes_with_time() const;

    /// Throws InputError if a listed boundary id occurs on no boundary face.
    void
    check_boundary_ids(const Triangulation<dim> &triangulation) const;

    std::vector<Dirichlet> dirichlet;
    std::vector<Neumann>   neumann;
    /// The loads (gravity, body force, tractions) are these times
    /// 'load_factor', lambda(t) at the time of the last set_time():
    /// consumers multiply by it.
    double load_factor = 1;
    /// Load continuation (time/quasistatic.cc): while set, the loads carry
    /// this factor instead of lambda(t), so that a quasistatic step can
    /// take part of its load increment at a time.
    std::optional<double> held_load_factor;
    /// Force per unit reference volume (N/m^3 if SI), added to rho_0 * gravity.
    std::unique_ptr<Function<dim>> body_force;
    /// Whether every body force expression is the literal "0".
    bool body_force_is_zero;
    /// Acceleration of gravity (m/s^2 if SI); multiplied by rho_0.
    Tensor<1, dim>                 gravity;
    std::unique_ptr<Function<dim>> initial_displacement;
    std::unique_ptr<Function<dim>> initial_velocity;

  private:
    /// lambda(t), a function of t only (evaluated at the origin).
    std::unique_ptr<Function<dim>> load_factor_function;
    /// Whether a Neumann, body force or load factor expression names t.
    bool loads_name_time_ = false;
    /// Whether the load factor expression names t.
    bool        factor_names_time = false;
    std::string factor_expression;
    std::string factor_note;
  };
} // namespace tissuefem::boundary
