#pragma once

#include <deal.II/lac/vector.h>

#include <tissuefem/base/parallel.h>
#include <tissuefem/materials/material_set.h>
#include <tissuefem/solid/discretization.h>
#include <tissuefem/solid/fibre_field.h>
#include <tissuefem/solid/formulations/interface.h>

namespace tissuefem::solid
{
  /**
   * Quantities computed from a displacement field for output and reports.
   * Each takes a ghosted displacement, works on the locally owned cells and
   * returns the global value on every process.
   */

  /**
   * Per-cell averages over quadrature points of J = det F and of the von
   * Mises equivalent of the Cauchy stress sigma = P F^T / J (computed from
   * the dim x dim stress: sqrt(3/2 dev(sigma) : dev(sigma)); in 1D |sigma|;
   * in 2D the out-of-plane stress is not included), with F the
   * formulation's effective one (@p deformation, Solid::deformation(); the
   * plain F if null). Entries of cells this process does not own are zero.
   */
  template <int dim>
  void
  cell_fields(const Discretization<dim>            &discretization,
              const materials::MaterialSet<dim>    &materials,
              const FibreField<dim>                &fibres,
              const formulations::Deformation<dim> *deformation,
              const VectorType                     &u,
              Vector<float>                        &jacobian,
              Vector<float>                        &von_mises);

  /// The smallest J = det F over all quadrature points.
  template <int dim>
  double
  min_jacobian(const Discretization<dim> &discretization, const VectorType &u);

  /**
   * How far the deformed body is from its rest shape up to a rigid motion:
   * the largest distance, over the mesh vertices, between X + u(X) and the
   * best-fitting rotation and translation of X (Kabsch: the rotation from
   * the SVD of the covariance, with det R = +1 so that mirror images count
   * as far). Length units.
   */
  template <int dim>
  double
  distance_from_rest_shape(const Discretization<dim> &discretization,
                           const VectorType          &u);
} // namespace tissuefem::solid
