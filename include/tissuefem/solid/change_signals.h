#pragma once

#include <boost/signals2/connection.hpp>
#include <boost/signals2/signal.hpp>

namespace tissuefem::solid
{
  /**
   * The announcements a solid makes when its mesh or its constraints
   * change (mesh adaptation, a tool grasping or letting go), in the manner
   * of deal.II's Triangulation::signals. What caches something built for
   * the old matrix, numbering or constraints connects here; the code that
   * changes the mesh or the constraints calls no one by hand.
   *
   * Both are emitted by Solid::setup(), once the solid exists:
   *  - about_to_change, before the matrix and the numbering are rebuilt:
   *    drop what refers to them (factorizations, preconditioners);
   *  - changed, after: rebuild what depends on them (an integrator's work
   *    vectors and masses, the near-null space of AMG) and bring state
   *    vectors to the new constraints. A mesh adaptation connects the
   *    transfer of the state to the new mesh at the front of this signal
   *    for the duration of the change, so that every other slot sees the
   *    state on the new mesh.
   */
  struct ChangeSignals
  {
    boost::signals2::signal<void()> about_to_change;
    boost::signals2::signal<void()> changed;
  };
} // namespace tissuefem::solid
