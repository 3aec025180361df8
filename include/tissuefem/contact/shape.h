#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <tissuefem/base/registry.h>
#include <tissuefem/contact/drawing.h>

#include <memory>
#include <string>
#include <type_traits>

namespace tissuefem::contact
{
  using namespace dealii;

  /**
   * Where a point is with respect to a rigid shape: the signed distance
   * (length units; positive outside the shape, negative inside), the unit
   * outward normal of the shape at the nearest surface point, and the
   * normal's derivative with respect to the point (1 / length units), the
   * curvature term of the contact tangent (zero for a plane).
   */
  template <int dim>
  struct Gap
  {
    double         distance = 0;
    Tensor<1, dim> normal;
    Tensor<2, dim> normal_gradient;
  };

  /**
   * A rigid shape at rest, in its own frame (the obstacle moves it,
   * obstacle.h). Each shape is one file pair: a class deriving from this
   * one, with a static declare_parameters(ParameterHandler &) that
   * declares the subsection named as the shape and a constructor taking
   * ParameterHandler & (positioned where that subsection was declared),
   * and optionally the parameter file's directory (const std::string &,
   * for shapes read from files), registered by TISSUEFEM_REGISTER_SHAPE.
   */
  template <int dim>
  class Shape
  {
  public:
    virtual ~Shape() = default;

    /// The gap of the point @p y (in the shape's frame).
    virtual Gap<dim>
    gap(const Point<dim> &y) const = 0;

    /// gap(y).distance alone: what contact asks of the many points that do
    /// not touch. Shapes whose normal and curvature cost more than their
    /// distance override it. It must be a true signed distance (changing
    /// by at most |dy| when y moves by dy): contact skips every point of a
    /// boundary face whose centre lies farther than the face's radius.
    virtual double
    distance(const Point<dim> &y) const
    {
      return gap(y).distance;
    }

    /// Triangles that draw it (drawing.h), in its own frame, for the live
    /// view. A shape without bounds (a half-space) is cut to a square (a
    /// segment in 2D, with a depth) of side @p extent about the point of
    /// its boundary nearest @p centre.
    virtual Drawing<dim>
    drawing(const Point<dim> &centre, const double extent) const = 0;
  };

  template <int dim>
  using ShapeRegistry
    = Registry<Shape<dim>, ParameterHandler &, const std::string &>;
} // namespace tissuefem::contact

/**
 * Registers the shape template @p Class (on dim) under @p name for dim = 1,
 * 2, 3, inside namespace tissuefem::contact at the end of its source file.
 */
#define TISSUEFEM_REGISTER_SHAPE(Class, name, description)                \
  namespace                                                               \
  {                                                                       \
    template <int dim>                                                    \
    bool tissuefem_register_shape_##Class()                               \
    {                                                                     \
      ShapeRegistry<dim>::instance().add(                                 \
        name,                                                             \
        description,                                                      \
        &Class<dim>::declare_parameters,                                  \
        [](ParameterHandler  &prm,                                        \
           const std::string &directory) -> std::unique_ptr<Shape<dim>> { \
          if constexpr (std::is_constructible_v<Class<dim>,               \
                                                ParameterHandler &,       \
                                                const std::string &>)     \
            return std::make_unique<Class<dim>>(prm, directory);          \
          else                                                            \
            {                                                             \
              (void)directory;                                            \
              return std::make_unique<Class<dim>>(prm);                   \
            }                                                             \
        });                                                               \
      return true;                                                        \
    }                                                                     \
    const bool tissuefem_registered_shape_##Class                         \
      = tissuefem_register_shape_##Class<1>()                             \
        && tissuefem_register_shape_##Class<2>()                          \
        && tissuefem_register_shape_##Class<3>();                         \
  }
