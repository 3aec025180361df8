#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/contact/boundary_points.h>
#include <tissuefem/contact/coulomb.h>
#include <tissuefem/contact/face_tree.h>
#include <tissuefem/contact/obstacle.h>
#include <tissuefem/forces/registry.h>
#include <tissuefem/solid/discretization.h>

#include <boost/signals2/connection.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

namespace tissuefem::contact
{
  /**
   * Frictionless contact between the tissue's boundary and rigid
   * obstacles, by a penalty (Wriggers 2006, chapters 4 and 6;
   * doc/user_guide.md, "Obstacles and contact"): at every
   * quadrature point of every boundary face, at its deformed position x =
   * X + u(X), each obstacle's gap g(x) (obstacle.h) where it is negative
   * costs the energy
   *
   *   E = sum over points of k / 2 g^2 dA,   k = factor E_tissue / h,
   *
   * dA the point's reference area weight, h the diameter of the point's
   * cell and E_tissue the largest Young's modulus of the materials, so
   * that the penetration under a given pressure p, p / k = p h / (factor
   * E_tissue), is a fixed fraction of the cell's own strain under p, on
   * any mesh and in any units. The force on the tissue is -dE/du = -k g n
   * dA per point (n the obstacle's outward normal), and its tangent
   * k (n (x) n + g dn/dx) dA per point pair of shape functions: the
   * consistent linearization, curvature included, so that Newton keeps
   * its quadratic convergence with contact active. Points at g <= 0 count
   * in the tangent (so that a body that just touches is held on the first
   * iteration), points at g < 0 in the force.
   *
   * With 'Method = augmented Lagrangian' each point carries a multiplier
   * lambda >= 0 (a pressure), the energy is (Powell-Hestenes-Rockafellar;
   * Wriggers 2006, chapter 6; Simo and Laursen 1992)
   *
   *   E = sum over points of p^2 / (2 k) dA,   p = max(0, lambda - k g),
   *
   * (up to a constant of lambda), whose force is p n dA and whose tangent
   * is k n (x) n - p dn/dx where p > 0, the penalty's at lambda = 0. After
   * each converged solve of a step, Uzawa's update lambda <- p moves the
   * multipliers towards the contact pressure, and the step is solved again
   * until every point's gap is within 'Gap tolerance' (|g| where it is
   * pressed, -g where it penetrates): the penetration then no longer
   * depends on the penalty, which only sets how fast the updates converge.
   * The multipliers carry over from step to step (a warm start) and are
   * dropped when the mesh changes.
   *
   * With an obstacle's 'Friction coefficient' mu > 0, a point in contact
   * also carries a stick point and a friction bound, and Coulomb's law
   * (coulomb.h) adds its tangential force, the traction of a tangential
   * spring from the stick point (k_t = 'Tangential penalty ratio' k) capped
   * at the bound. The bound is held fixed over a Newton solve, so that the
   * friction force has a potential and a symmetric tangent:
   * - with the augmented Lagrangian it is mu lambda, and the point also
   *   carries a tangential multiplier tau; Uzawa's update moves tau to the
   *   traction, and the step is solved again until tau moves by less than
   *   k_t times 'Gap tolerance' (a stuck point then slips by less than the
   *   tolerance);
   * - with the penalty it is mu p: after a converged solve the bound is set
   *   to mu times the point's pressure and the step solved again until it
   *   changes by less than k_t times 'Gap tolerance' (a fixed point on the
   *   bound, as the multipliers' updates are). A stuck point keeps the
   *   tangential spring's slip, up to mu p / k_t. Explicit steps take the
   *   bound of the step before (accept_step()).
   * A point that comes into contact during an implicit step sticks where
   * it was at the step's start (begin_step()), during an explicit step
   * where it ends it; the stick points of the points that slide move with
   * them only when a step is accepted (accept_step()).
   */
  template <int dim>
  class PenaltyContact : public forces::Interface<dim>
  {
  public:
    /// The obstacle slots (Obstacle::declare_parameters()) and 'Contact/
    /// Penalty factor', 'Method', 'Gap tolerance', 'Maximum multiplier
    /// updates', 'Start penetration tolerance' and 'Tangential penalty
    /// ratio'.
    static void
    declare_parameters(ParameterHandler &prm);

    /// Contact with the obstacles the file fills in (none: null), once the
    /// integrator chosen is found to honour the method chosen.
    static std::unique_ptr<forces::Interface<dim>>
    create(ParameterHandler &prm, const forces::SceneData<dim> &scene);

    /// With the obstacles @p obstacles of the scene (none: inactive) and
    /// the tissue's largest Young's modulus @p modulus (stress units).
    PenaltyContact(ParameterHandler                 &prm,
                   const solid::Discretization<dim> &discretization,
                   std::vector<Obstacle<dim>>        obstacles,
                   const double                      modulus);

    void
    add(const VectorType                &u,
        const double                     time,
        const bool                       jacobian,
        const AffineConstraints<double> &rows,
        const bool                       inhomogeneous,
        MatrixType                      &matrix,
        VectorType                      &residual) const override;

    double
    energy(const VectorType &u, const double time) const override;

    /**
     * Over every boundary face (any may touch): k |n . phi_i| sum_j |n .
     * phi_j| dA per point and obstacle, with |n_c| sum_d |n_d| <= (1 +
     * sqrt(dim)) / 2 over unit normals. The curvature term (-p dn/dx, of
     * relative size p / (k R)) is left out.
     */
    void
    add_stiffness_bound(VectorType &row_sums) const override;

    /// Restores the states of the last accepted step (a failed attempt's
    /// updates are dropped) and notes where the boundary points facing an
    /// obstacle with friction start the step.
    void
    begin_step(const VectorType &u, const double time) override;

    /// Moves the stick points of the points that slid and commits the
    /// states.
    void
    accept_step(const VectorType &u, const double time) override;

    /// Uzawa's update, with the augmented Lagrangian (see above).
    forces::Augmentation
    augment(const VectorType  &u,
            const double       time,
            const unsigned int update,
            std::string       &message) override;

    /// A body may rest on an obstacle.
    bool
    may_hold_body() const override
    {
      return !obstacle_list.empty();
    }

    /// Whether any obstacle moves.
    bool
    changes_with_time() const override
    {
      for (const auto &obstacle : obstacle_list)
        if (obstacle.moves)
          return true;
      return false;
    }

    /// What each obstacle does, summed over the processes.
    struct Report
    {
      std::string name;
      /// The resultant force of the obstacle on the tissue (force units).
      Tensor<1, dim> force;
      /// The largest penetration, max(-g, 0) (length units).
      double penetration = 0;
      /// The reference area carrying a contact pressure
      /// (length^(dim-1) units).
      double area = 0;
      /// The smallest and the largest contact pressure over the contact
      /// points that carry one (stress units; both 0 where none does).
      double min_pressure = 0, max_pressure = 0;
    };

    /// Every process calls (the reports sum over them). A run computes
    /// them once per state (Elasticity::postprocess()) and hands them to
    /// the tools and postprocessors with the step (postprocess::Step):
    /// with the augmented Lagrangian they depend on the multipliers of
    /// the moment, so they are not cached here.
    std::vector<Report>
    report(const VectorType &u, const double time) const;

    /// Refuses (InputError naming the obstacle's slot) an obstacle that
    /// starts deeper inside the tissue, at the ghosted @p u and @p time,
    /// than 'Contact/Start penetration tolerance'.
    void
    check_start(const VectorType &u, const double time) const;

    /**
     * Per active cell of this process (indexed by active cell index), for
     * the ghosted @p u at @p time: @p pressure, the largest contact
     * pressure at its boundary points (stress units; 0 on cells without
     * boundary faces), and @p gap, the smallest gap to any obstacle (length
     * units; negative where it penetrates) over its boundary points and its
     * centre (moved by the mean displacement of its vertices). For the VTU
     * output.
     */
    void
    cell_fields(const VectorType &u,
                const double      time,
                Vector<float>    &pressure,
                Vector<float>    &gap) const;

    const std::vector<Obstacle<dim>> &
    obstacles() const
    {
      return obstacle_list;
    }

    /// The obstacles, for a tool that moves one (Obstacle::follow()).
    std::vector<Obstacle<dim>> &
    obstacles()
    {
      return obstacle_list;
    }

    /// Whether it carries state from step to step (the augmented
    /// Lagrangian's multipliers, friction's stick points), which a
    /// checkpoint does not hold.
    bool
    keeps_history() const
    {
      return augmented || has_friction();
    }

  private:
    /// One contact point: obstacle index, gap, penalty stiffness k,
    /// reference area weight dA, point index q of the face, its key in
    /// the contact states, its pressure p = max(0, lambda - k g), whether
    /// it is active (lambda - k g >= 0), its position y in the obstacle's
    /// frame, the obstacle's pose (valid in for_each_face()'s callback),
    /// and with friction its stick point (null: none, obstacle's frame),
    /// friction bound (mu lambda, or the penalty's mu p of the last solve)
    /// and tangential multiplier tau (obstacle's frame).
    struct Point_
    {
      unsigned int      obstacle;
      Gap<dim>          gap;
      double            k;
      double            area;
      unsigned int      q;
      std::uint64_t     key;
      double            pressure;
      bool              active;
      Point<dim>        y;
      const Pose<dim>  *pose;
      const Point<dim> *anchor;
      double            bound;
      Tensor<1, dim>    tau;
    };

    /// What a contact point carries from solve to solve: its multiplier
    /// lambda (stress units) and, with friction, its tangential
    /// multiplier tau (stress units) and its stick point (in the
    /// obstacle's frame) once a step has been accepted in contact.
    struct State
    {
      double lambda = 0;
      /// The penalty method's friction bound, mu p (stress units).
      double         bound = 0;
      Tensor<1, dim> tau;
      bool           anchored = false;
      Point<dim>     anchor;
    };

    using Face = typename BoundaryPoints<dim>::Face;

    /**
     * Calls @p face(face, points) for each boundary face of each locally
     * owned cell with at least one point where lambda - k g >= 0 (g <= 0
     * without multipliers), or that carries a friction bound, for the
     * ghosted displacement @p u at @p time; with @p every, every point.
     */
    void
    for_each_face(const VectorType                                       &u,
                  const double                                            time,
                  const std::function<void(const Face &,
                                           const std::vector<Point_> &)> &face,
                  const bool every = false) const;

    /// Each obstacle's pose at @p time, in the obstacles' order.
    std::vector<Pose<dim>>
    poses_at(const double time) const;

    /**
     * The broad phase for the ghosted @p u, the obstacles' @p poses and
     * the largest multiplier of any point: refits the tree if the faces
     * have moved too far since its fit, queries it if the fit, the poses
     * or the multiplier changed since the last query, and returns in
     * @p motion the faces' motion since the fit (length units). The answer
     * is broad_phase.faces and .lower.
     */
    void
    update_broad_phase(const VectorType             &u,
                       const std::vector<Pose<dim>> &poses,
                       const double                  largest_multiplier,
                       double                       &motion) const;

    /// The penalty's fixed point on the friction bounds (augment()).
    forces::Augmentation
    update_bounds(const VectorType  &u,
                  const double       time,
                  const unsigned int update,
                  std::string       &message);

    /// Coulomb's law at the point @p p, which has a stick point.
    Coulomb<dim>
    friction(const Point_ &p) const;

    /// Whether some obstacle has friction.
    bool
    has_friction() const;

    const solid::Discretization<dim> &discretization;
    /// The boundary's contact points, cached per mesh.
    BoundaryPoints<dim>        boundary;
    std::vector<Obstacle<dim>> obstacle_list;
    double                     factor;
    double                     modulus;
    bool                       augmented;
    /// 'Gap tolerance' resolved to length units.
    double tolerance;
    /// 'Tangential penalty ratio'.
    double tangential;
    /// 'Start penetration tolerance' resolved to length units.
    double       start_tolerance;
    unsigned int max_updates;
    /// The states of the points that carry a multiplier, by key (active
    /// cell index, face, point, obstacle) on this process.
    std::unordered_map<std::uint64_t, State> states;
    /// The states as the last accepted step left them (accept_step()):
    /// where each attempt at a step starts (begin_step()).
    std::unordered_map<std::uint64_t, State> committed;
    /// With friction: where the boundary points were at the start of the
    /// step (obstacle frame), the stick point of those that come into
    /// contact in it.
    std::unordered_map<std::uint64_t, Point<dim>> step_start;
    /**
     * What for_each_face() keeps between calls for its broad phase: a tree
     * over the boundary faces (FaceTree), fitted to balls around each
     * face's points at the faces' displacement values of the last fit,
     * and the answer of its last query.
     * A face has moved by at most BoundaryPoints::motion_bound() since the
     * fit; the tree is refitted (one pass over the faces' points, the
     * hierarchy kept) once that motion exceeds a quarter of the faces'
     * mean diameter, and built anew when the faces change. A query asks
     * for the faces that may act for any motion up to that limit, so that
     * its answer serves every evaluation at the same fit, poses and
     * largest multiplier (the iterations of a step): each then passes over
     * the faces whose fitted clearance, less the motion, still exceeds
     * what may act.
     */
    struct BroadPhase
    {
      unsigned int        generation = 0;
      std::vector<double> reference;
      FaceTree<dim>       tree;
      /// The motion up to which the fit serves (length units).
      double limit = 0;
      /// Each face's key, for finding the face of a state's key.
      std::vector<std::uint64_t> keys;
      /// Fits so far, and the fit, poses and largest multiplier of the
      /// last query.
      unsigned int           fits = 0, queried_fit = 0;
      std::vector<Pose<dim>> queried_poses;
      double                 queried_multiplier = 0;
      /// The last query's answer: the faces that may act (ascending), and
      /// per face and obstacle the clearance g(c) - r of its fitted ball
      /// (length units).
      std::vector<unsigned int> faces;
      std::vector<double>       lower;
    };
    mutable BroadPhase broad_phase;
    /// Drops the states when the mesh changes.
    boost::signals2::scoped_connection mesh_changed;
  };

  /// Each obstacle's report at one state, in the obstacles' order (empty
  /// without obstacles).
  template <int dim>
  using Reports = std::vector<typename PenaltyContact<dim>::Report>;
} // namespace tissuefem::contact
