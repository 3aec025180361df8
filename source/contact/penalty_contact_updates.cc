#include <deal.II/base/mpi.h>

#include <tissuefem/base/nan_aware.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/contact/coulomb.h>
#include <tissuefem/contact/penalty_contact.h>

#include <cmath>
#include <sstream>

// PenaltyContact's updates between solves and steps: the augmented
// Lagrangian's multipliers, the penalty's friction bounds, and the stick
// points at a step's start and end (the class is in penalty_contact.h).
namespace tissuefem::contact
{
  namespace
  {
    /// Whether an update whose largest change on this process is @p worst
    /// (length units) settled the step (within @p tolerance), needs it
    /// solved again (fewer than @p max_updates so far), or gave up (with
    /// @p message: @p what, the change, the limits, and @p hint).
    forces::Augmentation
    verdict(double             worst,
            const double       tolerance,
            const unsigned int update,
            const unsigned int max_updates,
            const std::string &what,
            const std::string &hint,
            std::string       &message)
    {
      worst = mpi_max_keeping_nan(worst, parallel_tools::communicator());
      if (worst <= tolerance)
        return forces::Augmentation::satisfied;
      if (update + 1 < max_updates && std::isfinite(worst))
        return forces::Augmentation::again;
      std::ostringstream why;
      why << what << " " << worst << " (length units; 'Contact/Gap tolerance' "
          << tolerance << ") after " << update + 1
          << " updates ('Contact/Maximum multiplier updates'; a larger "
             "'Contact/Penalty factor' converges in fewer"
          << hint << ")";
      message = why.str();
      return forces::Augmentation::failed;
    }
  } // namespace


  template <int dim>
  forces::Augmentation
  PenaltyContact<dim>::augment(const VectorType  &u,
                               const double       time,
                               const unsigned int update,
                               std::string       &message)
  {
    if (!augmented)
      return has_friction() ? update_bounds(u, time, update, message)
                            : forces::Augmentation::satisfied;
    // Uzawa: lambda <- p and tau <- t at every point, stick points kept;
    // points left out have p = 0 and lose their state.
    std::unordered_map<std::uint64_t, State> updated;
    double                                   worst = 0;
    auto face = [&](const Face &, const std::vector<Point_> &points) {
      for (const Point_ &p : points)
        {
          const double g = p.gap.distance;
          worst = max_keeping_nan(worst, p.pressure > 0 ? std::abs(g) : -g);
          // A point that lifted off still felt friction in this solve
          // (its bound held over it): solve again without it.
          if (p.pressure == 0 && p.anchor && p.bound > 0)
            worst = max_keeping_nan(worst,
                                    friction(p).traction.norm()
                                      / (tangential * p.k));
          if (p.pressure > 0)
            {
              State state;
              if (const auto s = states.find(p.key); s != states.end())
                state = s->second;
              state.lambda = p.pressure;
              if (p.anchor)
                {
                  // tau <- t; how far it moves, over k, is the slip the
                  // penalty lets a stuck point take (length units).
                  const Tensor<1, dim> t = friction(p).traction;
                  worst
                    = max_keeping_nan(worst,
                                      (t - p.pose->world_vector(p.tau)).norm()
                                        / (tangential * p.k));
                  state.tau = p.pose->local_vector(t);
                }
              updated.emplace(p.key, state);
            }
        }
    };
    for_each_face(u, time, face);
    const forces::Augmentation outcome
      = verdict(worst,
                tolerance,
                update,
                max_updates,
                "the augmented Lagrangian left a gap (or a stuck point's "
                "slip) of",
                // Measured on the Hertz scene on P1 with 1e-9 m: the gap
                // hung at 4.8e-8 however many updates.
                "; a gap that no longer falls is one the faces cannot close "
                "at every quadrature point, as flat faces on a curved "
                "obstacle: raise 'Contact/Gap tolerance' above it",
                message);
    // Settled without friction: keep the multipliers the solution was
    // solved with, so that report() gives the force of that equilibrium.
    // Updated, they would add k g once more: after a mesh change
    // (multipliers 0) a first solve already within the tolerance reported
    // twice its force (the Hertz scene refined adaptively). With friction
    // the update stays: accept_step() moves a sliding point's stick point
    // to it, and its traction is then carried by tau = t alone.
    if (outcome != forces::Augmentation::satisfied || has_friction())
      states.swap(updated);
    return outcome;
  }


  template <int dim>
  forces::Augmentation
  PenaltyContact<dim>::update_bounds(const VectorType  &u,
                                     const double       time,
                                     const unsigned int update,
                                     std::string       &message)
  {
    // The penalty's friction bound <- mu p at every point in contact,
    // stick points kept; points that lost their pressure lose their state.
    std::unordered_map<std::uint64_t, State> updated;
    double                                   worst = 0;
    auto face = [&](const Face &, const std::vector<Point_> &points) {
      for (const Point_ &p : points)
        {
          const double mu = obstacle_list[p.obstacle].friction;
          if (mu == 0)
            continue;
          // How far the bound moves, over k_t: the change of the slip a
          // stuck point may take (length units).
          const double bound = mu * p.pressure;
          worst
            = max_keeping_nan(worst,
                              std::abs(bound - p.bound) / (tangential * p.k));
          if (p.pressure > 0)
            {
              State state;
              if (const auto s = states.find(p.key); s != states.end())
                state = s->second;
              state.bound = bound;
              updated.emplace(p.key, state);
            }
        }
    };
    for_each_face(u, time, face);
    states.swap(updated);
    return verdict(worst,
                   tolerance,
                   update,
                   max_updates,
                   "the friction bounds (mu times the contact pressure) "
                   "still moved, over the tangential penalty, by",
                   "",
                   message);
  }


  template <int dim>
  void
  PenaltyContact<dim>::begin_step(const VectorType &u, const double time)
  {
    // An attempt starts from the last accepted step: the multipliers and
    // stick points a failed attempt moved are dropped.
    states = committed;
    if (!has_friction())
      return;
    // Every boundary point, so that one that touches during the step,
    // however far it starts, sticks where it started. Collected apart:
    // for_each_face() reads step_start.
    std::unordered_map<std::uint64_t, Point<dim>> started;
    auto face = [&](const Face &, const std::vector<Point_> &points) {
      for (const Point_ &p : points)
        if (obstacle_list[p.obstacle].friction > 0)
          started.emplace(p.key, p.y);
    };
    for_each_face(u, time, face, true);
    step_start.swap(started);
  }


  template <int dim>
  void
  PenaltyContact<dim>::accept_step(const VectorType &u, const double time)
  {
    if (!has_friction())
      {
        committed = states;
        return;
      }
    // The stick points of the step's end: a point that slides takes its
    // stick point along (its traction stays on the friction bound); a
    // stuck one keeps it; one without takes where it is. With the penalty
    // the points in contact are those of the step's end, with the bound
    // mu p (which an explicit step's next force uses); the augmented
    // Lagrangian's are those of its last update.
    std::vector<std::pair<std::uint64_t, State>> moved;
    auto face = [&](const Face &, const std::vector<Point_> &points) {
      for (const Point_ &p : points)
        if (obstacle_list[p.obstacle].friction > 0 && p.pressure > 0)
          {
            State state;
            state.bound    = obstacle_list[p.obstacle].friction * p.pressure;
            state.anchored = true;
            state.anchor   = p.anchor ? *p.anchor : p.y;
            if (!p.anchor)
              {
                moved.emplace_back(p.key, state);
                continue;
              }
            if (const Coulomb<dim> law = friction(p); law.slides)
              {
                // The augmented Lagrangian's tau carries the traction; the
                // penalty's spring does, stretched to the bound behind the
                // point: t = -k_t (y - a) along the tangent plane.
                state.anchor = p.y;
                if (!augmented)
                  state.anchor
                    += p.pose->local_vector(law.traction) / (tangential * p.k);
              }
            moved.emplace_back(p.key, state);
          }
    };
    for_each_face(u, time, face);
    if (!augmented)
      states.clear();
    for (const auto &[key, state] : moved)
      if (!augmented)
        states.emplace(key, state);
      else if (const auto s = states.find(key); s != states.end())
        {
          s->second.anchor   = state.anchor;
          s->second.anchored = true;
        }
    committed = states;
  }


  template class PenaltyContact<1>;
  template class PenaltyContact<2>;
  template class PenaltyContact<3>;
} // namespace tissuefem::contact
