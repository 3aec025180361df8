#pragma once

#include <deal.II/base/parameter_handler.h>

#include <tissuefem/base/parallel.h>
#include <tissuefem/solid/operators.h>

#include <string>

namespace tissuefem::time
{
  using namespace dealii;

  /**
   * 'Damping ratio', the mass-proportional damping c = gamma/m of Jeffrey's
   * eq 10 (1/time unit, 1/s if SI), declared in the current subsection with
   * default 0 and @p documentation. The integrators with lumped masses all
   * take it; each says in its own words where the damping force acts.
   */
  void
  declare_damping_ratio(ParameterHandler  &prm,
                        const std::string &documentation);

  /// The documentation of 'Damping ratio' for the integrators that solve
  /// the first-order form (Radau IIA, ARKode).
  extern const char *const first_order_damping_documentation;

  /// 'Damping ratio' from the current subsection (no check).
  double
  get_damping_ratio(const ParameterHandler &prm);

  /// InputError naming @p section + "Damping ratio" unless @p damping is a
  /// finite number >= 0. Separate from get_damping_ratio() so that callers
  /// check it after leaving their subsections, in their own order of checks.
  void
  check_damping_ratio(const double damping, const std::string &section);

  /**
   * The pieces of the first-order form of Jeffrey's eq 10 that integrators
   * with lumped masses share (Radau IIA, ARKode):
   *
   *   u' = v,   v' = (f_ext(t) - f_int(u)) / m - c v.
   *
   * - damping(): c, the mass-proportional damping ratio (1/time unit); the
   *   damping force on dof i is -c m_i v_i.
   * - mass(): m, the solid's row-sum lumped mass, one entry per dof (mass
   *   units), checked to be positive (it is not for P2 simplices).
   * - free(): 1 on free dofs, 0 on constrained ones (dimensionless); the
   *   integrators multiply derivatives and Newton residuals with it, since
   *   constrained entries follow their prescribed values instead.
   *
   * Lumped masses are not condensed at hanging nodes, so reinit() refuses
   * a mesh with them. mass() refers to the solid's vector: call reinit()
   * again whenever the mesh changed.
   */
  class FirstOrderSystem
  {
  public:
    /**
     * @p integrator names the method in error messages ("Radau IIA"),
     * @p alternative is appended to the advice when the lumped mass is not
     * positive (e.g. " or backward Euler", or empty).
     */
    FirstOrderSystem(const double       damping,
                     const std::string &integrator,
                     const std::string &alternative = "");

    /// Checks the mesh, takes the lumped mass and builds free() laid out
    /// like @p like. Throws InputError for hanging nodes or a mass entry
    /// that is not positive.
    void
    reinit(solid::Operators &solid, const VectorType &like);

    double
    damping() const
    {
      return c;
    }

    const VectorType &
    mass() const
    {
      return *lumped;
    }

    const VectorType &
    free() const
    {
      return free_mask;
    }

    /// The power taken out by the damping force, c v^T m v (energy per
    /// time unit); 0 without damping. Collective over the processes.
    double
    damping_power(const VectorType &v) const;

  private:
    double            c;
    std::string       integrator, alternative;
    const VectorType *lumped = nullptr;
    VectorType        free_mask;
  };
} // namespace tissuefem::time
