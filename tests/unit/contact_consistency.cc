// Contact with rigid obstacles (contact/penalty_contact.h) is a force with a
// potential: its residual must be the gradient of implicit_energy() and its
// Jacobian the derivative of the residual, curvature term included, for
// Newton's quadratic convergence. Checked against central differences along
// random directions, on states where a sphere and a half-space both push
// into the boundary (several points in contact, others free), in 2D and
// 3D, on Q1, P1 and Q2 cells; and again with the augmented Lagrangian's
// multipliers taken from another state (Uzawa's update), so that points
// carry a pressure lambda - k g both where they penetrate and where their
// gap is open, and with Coulomb friction on the (flat) floor, stick points
// at that other state. Each time also the balance: the forces reported on
// the obstacles are minus the sum of the contact's nodal forces. On one
// and on two processes (random values per global index; the floor lies
// 0.1 above the corner, deeper than the random displacements of 0.03 can
// lift a boundary point near it, so that it touches on any numbering).

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/component_mask.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/app/parameters.h>

#include "../tests.h"
#include "solid_scene.h"

#include <limits>

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
      set Subdivisions = 4, 2, 2
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
        set Motion = 0.1 * t; -0.2 * t; 0
        set Rotation = )"
           + std::string(dim == 3 ? "0.3 * t; 0.2 * t; -0.4 * t" : "-0.4 * t")
           + R"(
        set Rotation centre = 0.5, 1, 0.2
        subsection sphere
          set Centre = 0.9, 1.35, 0.5
          set Radius = 0.5
        end
      end
      subsection Obstacle 3
        set Shape = half-space
        set Name  = floor
        set Rotation = )"
           + std::string(dim == 3 ? "0.05 * t; -0.1 * t; 0.08 * t" : "0.08 * t")
           + R"(
        set Rotation centre = 0.5, 0.1, 0.5
        subsection half-space
          set Point  = 0, 0.1, 0
          set Normal = 0.2, 1, 0.1
        end
      end
    end
    subsection Time integration
      set Integrator = backward Euler
    end
  )";
  }

  /**
   * Balance: the forces the obstacles report on the tissue (contact.csv,
   * and the tool force to come) sum to minus the contact's assembled
   * nodal residual, component by component, to round-off: what is applied
   * is what is reported. And the VTU's cell fields (largest pressure,
   * smallest gap) match contact.csv's.
   */
  template <int dim>
  void
  check_balance(tissuefem_tests::SolidScene<dim> &scene,
                const VectorType                 &u,
                const double                      t,
                const std::string                &label)
  {
    VectorType residual;
    scene.discretization->initialize_assembly_vector(residual);
    AffineConstraints<double> none;
    none.close();
    scene.obstacle_contact->add(
      u, t, false, none, false, scene.solid->jacobian(), residual);
    residual.compress(VectorOperation::add);
    Tensor<1, dim> reported;
    double         size = 0;
    for (const auto &report : scene.obstacle_contact->report(u, t))
      {
        reported += report.force;
        size += report.force.norm();
      }
    double worst = 0;
    for (unsigned int c = 0; c < dim; ++c)
      {
        ComponentMask mask(dim, false);
        mask.set(c, true);
        const IndexSet dofs
          = DoFTools::extract_dofs(scene.discretization->dof_handler, mask);
        double sum = 0;
        for (const auto i : residual.locally_owned_elements())
          if (dofs.is_element(i))
            sum += residual[i];
        sum   = Utilities::MPI::sum(sum, MPI_COMM_WORLD);
        worst = tissuefem::max_keeping_nan(worst, std::abs(sum + reported[c]));
      }
    tissuefem_tests::check_small(worst / size,
                                 1e-12,
                                 label
                                   + ": balance, the reported forces are "
                                     "minus the sum of the nodal forces");
    // The VTU's cell fields agree with contact.csv's figures (to float).
    Vector<float> pressure, gap;
    scene.obstacle_contact->cell_fields(u, t, pressure, gap);
    double highest = 0, deepest = 0;
    for (const auto &report : scene.obstacle_contact->report(u, t))
      {
        highest = std::max(highest, report.max_pressure);
        deepest = std::max(deepest, report.penetration);
      }
    // Each process fills its own cells (0 elsewhere).
    double smallest_gap = std::numeric_limits<double>::infinity();
    for (const auto &cell :
         scene.discretization->dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        smallest_gap
          = std::min<double>(smallest_gap, gap[cell->active_cell_index()]);
    smallest_gap = Utilities::MPI::min(smallest_gap, MPI_COMM_WORLD);
    const double largest_pressure
      = Utilities::MPI::max(double(pressure.linfty_norm()), MPI_COMM_WORLD);
    tissuefem_tests::check_small(
      (largest_pressure - highest) / highest,
      1e-6,
      label + ": the VTU's largest contact pressure is contact.csv's");
    tissuefem_tests::check_small(
      (smallest_gap + deepest) / deepest,
      1e-6,
      label + ": the VTU's smallest gap is minus contact.csv's penetration");
  }

  template <int dim>
  void
  check(const std::string &name, const std::string &text)
  {
    for (const bool augmented : {false, true})
      {
        ParameterHandler prm;
        declare_all_parameters(prm);
        prm.parse_input_from_string(text);
        if (augmented)
          prm.parse_input_from_string(
            "subsection Contact\n set Method = augmented Lagrangian\n"
            " subsection Obstacle 3\n  set Friction coefficient = 0.4\n"
            " end\nend\n",
            "",
            true);
        tissuefem_tests::SolidScene<dim> scene(prm);
        auto                            &solid = *scene.solid;
        VectorType                       u, u_tilde, d;
        solid.initialize_vector(u);
        solid.initialize_vector(u_tilde);
        solid.initialize_vector(d);
        // Random values drawn per global index, so that each process
        // draws its own entries (the numbering, and so the field, differs
        // between one and two processes; every check holds for any field).
        for (const auto i : u.locally_owned_elements())
          {
            tissuefem_tests::Random random(20261126 + 7919 * i);
            random.uniform();
            u[i]       = 0.03 * random.uniform();
            u_tilde[i] = 0.01 * random.uniform();
            d[i]       = random.uniform();
          }
        u.compress(VectorOperation::insert);
        u_tilde.compress(VectorOperation::insert);
        d.compress(VectorOperation::insert);
        // The contribution itself reads ghosted vectors (the solid ghosts
        // its arguments).
        VectorType ghosted;
        scene.discretization->initialize_vector(ghosted, true);
        ghosted             = u;
        const double      c = 3., t = 0.7;
        const std::string label
          = name + (augmented ? ", augmented Lagrangian" : ", penalty");
        if (augmented)
          {
            // Multipliers from u shifted by 0.3 % of the body towards the
            // obstacles' side: at u, some carry a pressure across an open
            // gap.
            VectorType  shifted(u);
            std::string message;
            for (const auto i : shifted.locally_owned_elements())
              shifted[i] -= 0.006;
            shifted.compress(VectorOperation::add);
            // The step starts there: the floor's stick points.
            solid.begin_step(shifted, t);
            tissuefem_tests::check(solid.augment(shifted, t, 0, message)
                                     == forces::Augmentation::again,
                                   label + ": the multipliers move",
                                   message);
          }
        // Contact is active: some points of both obstacles carry a
        // pressure.
        for (const auto &report : scene.obstacle_contact->report(ghosted, t))
          tissuefem_tests::check(report.area > 0 && report.max_pressure > 0,
                                 label + ": obstacle " + report.name
                                   + " touches the tissue",
                                 "area " + std::to_string(report.area));
        check_balance<dim>(scene, ghosted, t, label);
        tissuefem_tests::check_derivatives(solid, u, u_tilde, c, t, d, label);
      }
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const tissuefem_tests::OneWriter one_writer;
  check<2>("Q1, 2D", scene(2, "hypercube", 1));
  check<2>("Q2, 2D", scene(2, "hypercube", 2));
  check<2>("P1, 2D", scene(2, "simplex", 1));
  check<3>("Q1, 3D", scene(3, "hypercube", 1));
  check<3>("P1, 3D", scene(3, "simplex", 1));
  return tissuefem_tests::exit_status();
}
