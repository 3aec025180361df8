#pragma once

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/base/trajectory_table.h>
#include <tissuefem/contact/shape.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tissuefem::contact
{
  /**
   * A rigid obstacle of the scene: a named shape (shape.h) translated by a
   * motion given as expressions of t. Declared in 'Contact/Obstacle k',
   * k = 1..max_obstacles, each with its own 'Shape' (none by default), so
   * that a scene has as many obstacles as it fills in.
   */
  template <int dim>
  class Obstacle
  {
  public:
    /// The slots 'Contact/Obstacle k' and, inside each, every registered
    /// shape's own subsection.
    static void
    declare_parameters(ParameterHandler &prm);

    /// The obstacles the file asks for, in slot order; shapes read from
    /// files take relative paths from @p directory (the parameter file's).
    static std::vector<Obstacle<dim>>
    create_all(ParameterHandler &prm, const std::string &directory = "");

    /// The shape's translation at @p time (length units).
    Tensor<1, dim>
    offset(const double time) const;

    /// The gap of the point @p x with the shape translated by @p offset
    /// (shape.h).
    Gap<dim>
    gap(const Point<dim> &x, const Tensor<1, dim> &offset) const
    {
      return shape->gap(x - offset);
    }

    /// Its signed distance alone (Shape::distance()).
    double
    distance(const Point<dim> &x, const Tensor<1, dim> &offset) const
    {
      return shape->distance(x - offset);
    }

    /// Makes the shape follow @p motion (a translation against time, length
    /// units; a live device's) instead of its parameters' motion.
    void
    follow(std::function<Tensor<1, dim>(const double)> motion)
    {
      follower = std::move(motion);
      moves    = true;
    }

    /// Whether its parameters give it a motion ('Motion' names t or a
    /// 'Motion file' is set).
    bool
    has_own_motion() const
    {
      return recorded || own_motion_names_t;
    }

    /// The name it carries in every output.
    std::string name;

    /// Its subsection, 'Contact/Obstacle k', for messages.
    std::string slot;

    /// Coulomb's friction coefficient between it and the tissue
    /// (dimensionless; 0: frictionless).
    double friction = 0;

    /// Whether its motion names t.
    bool moves = false;

  private:
    std::shared_ptr<const Shape<dim>>    shape;
    std::shared_ptr<FunctionParser<dim>> motion;
    /// 'Motion file' (null: 'Motion').
    std::shared_ptr<const TrajectoryTable<dim>> recorded;
    /// A motion set by follow() (empty: the parameters').
    std::function<Tensor<1, dim>(const double)> follower;
    bool                                        own_motion_names_t = false;
  };

  /// Slots 'Obstacle 1' .. 'Obstacle max_obstacles' in 'Contact'.
  constexpr unsigned int max_obstacles = 4;
} // namespace tissuefem::contact
