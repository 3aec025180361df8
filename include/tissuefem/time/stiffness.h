#pragma once

#include <tissuefem/base/parallel.h>
#include <tissuefem/solid/operators.h>

#include <string>

namespace tissuefem::time
{
  /**
   * The stiffness K(u) = d f_int / du that implicit Runge-Kutta methods put
   * into their Newton matrices, computed the way Jeffrey's appendix E
   * compares (Table E.1):
   * - "analytical": the solid's tangent (automatic differentiation of the
   *   stress), assembled;
   * - "numerical": forward differences of the internal force, one force
   *   evaluation per group of columns that share no row
   *   (Operators::column_groups()), written into the same sparsity pattern;
   * - "simplified": no stiffness at all (the Newton matrix keeps only mass
   *   and damping and is never assembled).
   * Rows and columns of constrained degrees of freedom hold only a
   * positive diagonal.
   */
  class Stiffness
  {
  public:
    /// @p kind is one of the three names above.
    explicit Stiffness(const std::string &kind);

    bool
    assembled() const
    {
      return kind != "simplified";
    }

    /// Evaluates K at (u, time) into matrix() (no-op for "simplified").
    void
    evaluate(solid::Operators &solid, const VectorType &u, const double time);

    const MatrixType &
    matrix() const
    {
      return stiffness;
    }

    /// Forget the matrix layout (the mesh changed).
    void
    reset()
    {
      layout_ready = false;
    }

    static const char *
    choices()
    {
      return "analytical|numerical|simplified";
    }

  private:
    std::string kind;
    MatrixType  stiffness;
    bool        layout_ready = false;
    /// colour[j]: the column group of dof j.
    std::vector<unsigned int> colour;
  };
} // namespace tissuefem::time
