// Contact's broad phase (contact/penalty_contact.h, BroadPhase): a tree
// over the boundary faces, refitted only once the faces have moved by more
// than a quarter of their mean diameter, finds the faces within reach of
// each obstacle. Skipping the rest must change nothing: along a sequence of
// states, the contact energy, residual and reports of one PenaltyContact
// that keeps its tree from state to state must equal, to round-off, those
// of a fresh one (built from the same parameters, nothing kept) at the same
// state. The sequences bring faces into contact after a fit in three ways:
// the tissue moving by steps small enough for the fit to be kept (the
// faces' motion bound), the obstacles translating towards the tissue with
// the tissue still, both, and the floor turning towards the tissue about a
// distant pivot; in 2D and 3D, on P1, Q1 and Q2 cells (Q2's shape functions
// take negative values: the bound's factor L), with the penalty and the
// augmented Lagrangian (multipliers from an earlier state). Also: the share
// of states at which some obstacle touches, so that the sequences cross
// into contact. The cells are 0.25 wide and 1 tall, so that a face's own
// radius (a margin the ball has built in) is small against the motion
// allowed between two fits (a quarter of the cell's diameter): with the
// tissue's motion bound left out of the tree's queries in the library, the
// kept contact misses faces and this test fails.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/component_mask.h>

#include <tissuefem/app/parameters.h>

#include "../tests.h"
#include "solid_scene.h"

#include <cmath>
#include <string>

using namespace dealii;
using namespace tissuefem;

namespace
{
  std::string
  scene(const int dim, const std::string &cells, const int degree)
  {
    return "set Dimension = " + std::to_string(dim) + R"(
    subsection Geometry
      set Cell type    = )"
           + cells + R"(
      set Lower corner = 0, 0, 0
      set Upper corner = 2, 1, 1
      set Subdivisions = 8, 1, 4
    end
    subsection Finite element
      set Polynomial degree = )"
           + std::to_string(degree) + R"(
    end
    subsection Materials
      set Model           = neo-Hookean
      set Young's modulus = 10
      set Poisson's ratio = 0.3
    end
    subsection Contact
      set Penalty factor = 30
      subsection Obstacle 1
        set Shape  = sphere
        set Name   = probe
        set Motion = 0.02 * t; -0.3 * t; 0
        subsection sphere
          set Centre = 0.9, 1.45, 0.5
          set Radius = 0.4
        end
      end
      subsection Obstacle 2
        set Shape = half-space
        set Name  = floor
        set Motion = 0; 0.2 * t; 0
        subsection half-space
          set Point  = 0, -0.15, 0
          set Normal = 0.2, 1, 0.1
        end
      end
    end
    subsection Time integration
      set Integrator = backward Euler
    end
  )";
  }

  /// The energy, the residual's entries and the reported forces of @p
  /// scene's contact at (@p u, @p t), in one list.
  template <int dim>
  std::vector<double>
  evaluate(tissuefem_tests::SolidScene<dim> &scene,
           const VectorType                 &u,
           const double                      t)
  {
    auto      &contact = *scene.obstacle_contact;
    VectorType residual;
    scene.discretization->initialize_assembly_vector(residual);
    AffineConstraints<double> none;
    none.close();
    contact.add(u, t, false, none, false, scene.solid->jacobian(), residual);
    residual.compress(VectorOperation::add);
    std::vector<double> values{contact.energy(u, t)};
    for (const auto i : residual.locally_owned_elements())
      values.push_back(residual[i]);
    for (const auto &report : contact.report(u, t))
      for (unsigned int d = 0; d < dim; ++d)
        values.push_back(report.force[d]);
    return values;
  }

  template <int dim>
  void
  check(const std::string &name, const std::string &text)
  {
    for (const bool augmented : {false, true})
      for (const std::string motion :
           {"tissue", "obstacles", "both", "turning floor"})
        {
          ParameterHandler prm;
          declare_all_parameters(prm);
          prm.parse_input_from_string(text);
          if (motion == "turning floor")
            // The floor still, turned about a pivot 3 to 5 left of the
            // tissue: it rises under the tissue by up to 0.3 over the
            // sequence, through its rotation alone.
            prm.parse_input_from_string(
              std::string("subsection Contact\n subsection Obstacle 2\n"
                          "  set Motion = 0\n  set Rotation = ")
                + (dim == 3 ? "0; 0; 0.06 * t" : "0.06 * t")
                + "\n  set Rotation centre = -3, -0.15, 0.5\n end\nend\n",
              "",
              true);
          if (augmented)
            prm.parse_input_from_string(
              "subsection Contact\n set Method = augmented Lagrangian\nend\n",
              "",
              true);
          tissuefem_tests::SolidScene<dim> kept(prm);
          tissuefem_tests::Random          random(20261128);
          VectorType                       u, direction;
          kept.solid->initialize_vector(u);
          kept.solid->initialize_vector(direction);
          // Up (towards the sphere) at 1 per unit, with noise of 0.5.
          ComponentMask up(dim, false);
          up.set(1, true);
          const IndexSet lifted
            = DoFTools::extract_dofs(kept.discretization->dof_handler, up);
          for (const auto i : u.locally_owned_elements())
            direction[i]
              = 0.5 * random.uniform() + (lifted.is_element(i) ? 1. : 0.);
          if (augmented)
            {
              // Multipliers from a state pressed further: some points
              // carry a pressure across an open gap.
              std::string message;
              kept.solid->augment(u, 0.2, 0, message);
            }
          // Moving the tissue alone: the sphere 0.02 above it.
          double       worst = 0, t = motion == "tissue" ? 0.1 : 0;
          unsigned int touching = 0, states = 0;
          // 60 states: each entry of the tissue's displacement moves by
          // up to 3e-3 per state (2e-3 up, noise 1e-3; a quarter of the
          // faces' mean diameter is about 0.06 here, so the clearances are
          // kept over many states), the sphere by 0.36 and the floor by
          // 0.24 over the sequence.
          for (unsigned int k = 0; k < 60; ++k, ++states)
            {
              if (motion == "tissue" || motion == "both")
                u.add(2e-3, direction);
              if (motion != "tissue")
                t += 0.02;
              VectorType ghosted;
              kept.discretization->initialize_vector(ghosted, true);
              ghosted         = u;
              const auto with = evaluate(kept, ghosted, t);
              // The augmented Lagrangian's multipliers are state: the fresh
              // contact takes the same ones (its own update at the same
              // state), everything else from nothing.
              tissuefem_tests::SolidScene<dim> fresh(prm);
              if (augmented)
                {
                  VectorType zero;
                  fresh.solid->initialize_vector(zero);
                  std::string message;
                  fresh.solid->augment(zero, 0.2, 0, message);
                }
              const auto without = evaluate(fresh, ghosted, t);
              double     size    = 0;
              for (const double v : without)
                size = std::max(size, std::abs(v));
              if (with.size() != without.size())
                worst = std::numeric_limits<double>::infinity();
              else
                for (unsigned int i = 0; i < with.size(); ++i)
                  tissuefem_tests::raise(worst,
                                         std::abs(with[i] - without[i])
                                           / std::max(size, 1e-300));
              touching += with[0] > 0 ? 1 : 0;
            }
          const std::string label
            = name + (augmented ? ", augmented Lagrangian" : ", penalty")
              + ", moving " + motion;
          tissuefem_tests::check_small(
            worst,
            1e-13,
            label
              + ": contact with kept clearances equals a fresh evaluation "
                "(largest difference over the largest value)");
          tissuefem_tests::check(touching > 0 && touching < states,
                                 label + ": the sequence crosses into contact",
                                 std::to_string(touching) + " of "
                                   + std::to_string(states) + " touching");
        }
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const tissuefem_tests::OneWriter one_writer;
  check<2>("Q2, 2D", scene(2, "hypercube", 2));
  check<2>("P1, 2D", scene(2, "simplex", 1));
  check<3>("Q1, 3D", scene(3, "hypercube", 1));
  check<3>("P1, 3D", scene(3, "simplex", 1));
  return tissuefem_tests::exit_status();
}
