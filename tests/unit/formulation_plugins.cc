// Element formulations are plugins (solid/formulations/interface.h): one
// registered outside the library (here 'stiffer', the displacement element
// with its stress and tangent doubled) is a choice of 'Materials/Formulation'
// beside the library's own, the solid creates it by name, and its cell
// terms are what the cell loop contracts, Jacobian included.
// Expected values: a 1D bar (0, 1), linear elastic with E = 1, clamped at
// x = 0, under its own weight rho g = -0.1, quasistatic: u(x) = -0.1 (x -
// x^2 / 2) / E_eff, exact at the nodes of linear elements in 1D (as
// tests/prm/gravity_ramp_bar_1d): u(1) = -0.05 with the displacement
// element, and -0.025 with 'stiffer' (E_eff = 2). The linear model makes the
// problem linear: a consistent tangent converges in one Newton iteration,
// which the run's report gives.

#include <deal.II/base/mpi.h>

#include <tissuefem/solid/formulations/displacement.h>

#include "../run_program.h"
#include "../tests.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

using namespace dealii;
using namespace tissuefem;

namespace
{
  /// The displacement element with twice its stress and tangent; on the
  /// general quadrature loop (the lean kernel computes the displacement
  /// element's own terms).
  template <int dim>
  class Stiffer : public solid::formulations::Displacement<dim>
  {
  public:
    typename solid::formulations::Interface<dim>::LeanKernel
    lean_kernel() const override
    {
      return solid::formulations::Interface<dim>::LeanKernel::none;
    }

    bool
    cell_terms(const solid::formulations::Context<dim> &context,
               solid::formulations::CellTerms<dim>     &cell) const override
    {
      solid::formulations::Displacement<dim>::cell_terms(context, cell);
      for (unsigned int q = 0; q < cell.P.size(); ++q)
        {
          cell.P[q] *= 2;
          if (cell.jacobian)
            cell.A[q] *= 2;
        }
      return true;
    }
  };

  template class Stiffer<1>;
  template class Stiffer<2>;
  template class Stiffer<3>;

  TISSUEFEM_REGISTER_FORMULATION(Stiffer,
                                 "stiffer",
                                 "a test formulation: the displacement "
                                 "element's stress and tangent doubled.")

  const char *scene = R"(set Dimension = 1
subsection Geometry
  set Lower corner = 0
  set Upper corner = 1
  set Subdivisions = 4
end
subsection Materials
  set Model           = linear elastic
  set Young's modulus = 1
  set Poisson's ratio = 0
  set Density         = 0.1
end
subsection Boundary conditions
  set Dirichlet   = 0: x: 0
  set Gravity     = -1
  set Load factor = 1
end
subsection Time integration
  set Integrator = quasistatic
  set End time   = 1
  set Time step  = 1
end
subsection Output
  set Directory    = results
  subsection VTU
    set Interval = 0
  end
  subsection Probes
    set Points = 1
  end
end
)";

  /// Runs the scene with @p formulation; returns the exit status.
  int
  run(const std::string &formulation)
  {
    std::filesystem::remove_all("results");
    {
      std::ofstream file("scene.prm");
      file << scene
           << "subsection Materials\n  set Formulation = " << formulation
           << "\nend\n";
    }
    return tissuefem_tests::run_program({"scene.prm"});
  }

  /// The last probe value of probes.csv (time,probe,X,ux).
  double
  tip_displacement()
  {
    std::ifstream in("results/probes.csv");
    std::string   line, last;
    while (std::getline(in, line))
      if (!line.empty())
        last = line;
    return std::stod(last.substr(last.rfind(',') + 1));
  }

  /// The value of @p key in run.txt ('key = value  # unit').
  double
  run_figure(const std::string &key)
  {
    std::ifstream in("results/run.txt");
    std::string   line;
    while (std::getline(in, line))
      if (line.rfind(key + " = ", 0) == 0)
        return std::stod(line.substr(key.size() + 3));
    return std::nan("");
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;

  // The choices come from the registry: the library's and the test's.
  const std::string choices
    = solid::formulations::FormulationRegistry<1>::instance()
        .selection_pattern();
  if (root)
    for (const std::string name : {"displacement",
                                   "mean dilatation",
                                   "nodal dilatation",
                                   "edge length",
                                   "stiffer"})
      tissuefem_tests::check(("|" + choices + "|").find("|" + name + "|")
                               != std::string::npos,
                             "'" + name + "' is a choice of Formulation",
                             choices);

  for (const auto &[formulation, expected] :
       {std::pair<std::string, double>{"displacement", -0.05},
        {"stiffer", -0.025}})
    {
      const int status = run(formulation);
      if (!root)
        continue;
      const double tip   = tip_displacement();
      const double error = std::abs(tip - expected) / std::abs(expected);
      tissuefem_tests::check(status == 0,
                             formulation + ": the run completes",
                             "exit " + std::to_string(status));
      tissuefem_tests::check_small(
        error, 1e-10, formulation + ": u(1) against the closed form, relative");
      // One Newton iteration per step: the tangent is the residual's.
      const double iterations = run_figure("newton iterations");
      tissuefem_tests::check(iterations == run_figure("steps"),
                             formulation + ": one Newton iteration a step",
                             std::to_string(iterations) + " iterations");
    }
  return tissuefem_tests::exit_status();
}
