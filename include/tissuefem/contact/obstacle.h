#pragma once

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/base/trajectory_table.h>
#include <tissuefem/contact/pose.h>
#include <tissuefem/contact/shape.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tissuefem::contact
{
  /**
   * A rigid obstacle of the scene: a named shape (shape.h) moved rigidly by
   * a pose (pose.h) against time: a translation and a rotation about a
   * centre, each given as expressions of t or read together from a file of
   * poses, the translation possibly a live device's. Declared in
   * 'Contact/Obstacle k',
   * k = 1..obstacle_slots(), each with its own 'Shape' (none by default),
   * so that a scene has as many obstacles as it fills in.
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

    /// Where the shape is at @p time.
    Pose<dim>
    pose(const double time) const;

    /// The gap of the point @p x with the shape at @p pose (shape.h), in
    /// the world's frame.
    Gap<dim>
    gap(const Point<dim> &x, const Pose<dim> &pose) const
    {
      return pose.world_gap(shape->gap(pose.local(x)));
    }

    /// Its signed distance alone (Shape::distance()).
    double
    distance(const Point<dim> &x, const Pose<dim> &pose) const
    {
      return shape->distance(pose.local(x));
    }

    /// Triangles that draw its shape, in the shape's frame (the pose moves
    /// them; Shape::drawing()); a shape without bounds is cut to a square of
    /// side @p extent about the point nearest @p centre (the world's, at
    /// time 0).
    Drawing<dim>
    drawing(const Point<dim> &centre, const double extent) const
    {
      return shape->drawing(pose(0.).local(centre), extent);
    }

    /// Makes the shape follow @p motion (a translation against time, length
    /// units; a live device's) instead of its parameters' translation (its
    /// rotation stays the parameters').
    void
    follow(std::function<Tensor<1, dim>(const double)> motion)
    {
      follower = std::move(motion);
      moves    = true;
    }

    /// Whether its parameters give it a translation ('Motion' names t or
    /// a 'Motion file' is set).
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

    /// Whether its pose changes with time.
    bool moves = false;

  private:
    /// Reads 'Rotation' and 'Rotation centre' of the slot @p slot.
    void
    read_rotation(ParameterHandler &prm, const std::string &slot);

    std::shared_ptr<const Shape<dim>>    shape;
    std::shared_ptr<FunctionParser<dim>> motion;
    /// 'Rotation' (null in 1D).
    std::shared_ptr<FunctionParser<dim>> rotation;
    /// 'Rotation centre', in the shape's frame.
    Point<dim> pivot;
    bool       rotating = false;
    /// 'Motion file' (null: 'Motion' and 'Rotation').
    std::shared_ptr<const TrajectoryTable<dim>> recorded;
    /// A motion set by follow() (empty: the parameters').
    std::function<Tensor<1, dim>(const double)> follower;
    bool                                        own_motion_names_t = false;
  };

  /// Slots 'Obstacle 1' .. 'Obstacle max_obstacles' in 'Contact' are
  /// always declared (--print-parameters lists them).
  constexpr unsigned int max_obstacles = 4;

  /// The largest k a run may name in 'Obstacle k': a typo's 'Obstacle
  /// 100000' is refused instead of declared.
  constexpr unsigned int largest_obstacle_slot = 100;

  /// The slots Obstacle::declare_parameters() declares: max_obstacles, or
  /// more once name_obstacle_slot() has seen them named. It only rises;
  /// Obstacle::create_all() reads the slots its handler declared.
  unsigned int
  obstacle_slots();

  /**
   * Raises obstacle_slots() to @p k (the digits of 'Obstacle k' in a
   * parameter file's 'subsection' line or a --set path), so that a run
   * declares every slot its file names before reading it
   * (ParameterHandler reads only what was declared). Throws an InputError
   * naming @p where for k = 0 or k > largest_obstacle_slot.
   */
  void
  name_obstacle_slot(const std::string &k, const std::string &where);
} // namespace tissuefem::contact
