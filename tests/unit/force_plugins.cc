// Force contributions are plugins (forces/registry.h): a kind registered
// outside the library (here a spring that ties the free end of a bar to
// the ground, energy k u(L)^2 / 2) is created by the scene when its
// subsection asks for it, beside the library's own kinds, and the solid
// takes its residual, Jacobian and energy.
// Expected values (a closed form): a 1D bar (0, 1), linear elastic with
// E = 1, nu = 0, clamped at x = 0, pulled at x = 1 by the traction
// T = 0.1 (quasistatic, the load ramping to its full size at t = 1). The
// strain is uniform, E u(1) / L + k u(1) = T: u(1) = 0.1 / (1 + k),
// u(1/2) = u(1) / 2, which linear elements represent exactly; without
// the spring u(1) = 0.1.

#include <deal.II/base/mpi.h>

#include <tissuefem/app/parameters.h>
#include <tissuefem/forces/registry.h>
#include <tissuefem/scene/scene.h>

#include "../run_program.h"
#include "../tests.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

using namespace dealii;
using namespace tissuefem;

namespace
{
  /// The spring: E = k u(X)^2 / 2 on the first component of the vertex
  /// at X = 'End spring/Position' (1D).
  template <int dim>
  class EndSpring : public forces::Interface<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("End spring");
      prm.declare_entry("Stiffness",
                        "0",
                        Patterns::Double(0),
                        "k (force per length; 0: no spring).");
      prm.leave_subsection();
    }

    static std::unique_ptr<forces::Interface<dim>>
    create(ParameterHandler &prm, const forces::SceneData<dim> &scene)
    {
      prm.enter_subsection("End spring");
      const double k = prm.get_double("Stiffness");
      prm.leave_subsection();
      if (k == 0)
        return nullptr;
      scene.notes.push_back("end spring k = " + std::to_string(k));
      return std::make_unique<EndSpring<dim>>(scene.discretization, k);
    }

    EndSpring(const solid::Discretization<dim> &discretization, const double k)
        : discretization(discretization)
        , k(k)
    {
    }

    void
    add(const VectorType                &u,
        const double                     time,
        const bool                       jacobian,
        const AffineConstraints<double> &rows,
        const bool                       inhomogeneous,
        MatrixType                      &matrix,
        VectorType                      &residual) const override
    {
      (void)time;
      (void)inhomogeneous;
      if (const auto dof = end_dof())
        {
          FullMatrix<double> K(1, 1);
          Vector<double>     r(1);
          K(0, 0) = k;
          r(0)    = k * u(*dof);
          const std::vector<types::global_dof_index> dofs{*dof};
          if (jacobian)
            rows.distribute_local_to_global(K, r, dofs, matrix, residual);
          else
            rows.distribute_local_to_global(r, dofs, residual);
        }
    }

    double
    energy(const VectorType &u, const double time) const override
    {
      (void)time;
      const auto dof = end_dof();
      return Utilities::MPI::sum(dof ? 0.5 * k * u(*dof) * u(*dof) : 0.,
                                 MPI_COMM_WORLD);
    }

  private:
    /// The dof of u_x at the vertex X = 1 if this process owns its cell.
    std::optional<types::global_dof_index>
    end_dof() const
    {
      for (const auto &cell :
           discretization.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int v : cell->vertex_indices())
            if (std::abs(cell->vertex(v)[0] - 1) < 1e-12)
              return cell->vertex_dof_index(v, 0);
      return std::nullopt;
    }

    const solid::Discretization<dim> &discretization;
    const double                      k;
  };

  template class EndSpring<1>;
  template class EndSpring<2>;
  template class EndSpring<3>;

  TISSUEFEM_REGISTER_FORCE_CONTRIBUTION(EndSpring,
                                        "end spring",
                                        "a test spring.")

  const char *bar = R"(set Dimension = 1
subsection Geometry
  set Lower corner = 0
  set Upper corner = 1
  set Subdivisions = 4
end
subsection Materials
  set Model           = linear elastic
  set Young's modulus = 1
  set Poisson's ratio = 0
end
subsection Boundary conditions
  set Dirichlet = 0: x: 0
  set Neumann   = 1: 0.1
end
subsection Time integration
  set Integrator = quasistatic
  set End time   = 1
  set Time step  = 0.5
end
subsection Output
  set Directory = results
  subsection VTU
    set Interval = 0
  end
  subsection Probes
    set Points = 0.5; 1
  end
end
)";

  /// Writes the bar with the spring's @p stiffness to scene.prm.
  void
  write_scene(const double stiffness)
  {
    std::ofstream file("scene.prm");
    file << bar << "subsection End spring\n  set Stiffness = " << stiffness
         << "\nend\n";
  }

  /// The last row's u_x of each probe of results/probes.csv (columns
  /// time, probe, X, ux).
  std::vector<double>
  final_probes()
  {
    std::vector<double> u(2, std::nan(""));
    std::ifstream       in("results/probes.csv");
    std::string         line;
    std::getline(in, line);
    while (std::getline(in, line))
      {
        std::vector<double> row;
        std::istringstream  fields(line);
        for (std::string f; std::getline(fields, f, ',');)
          row.push_back(std::stod(f));
        if (row.size() == 4 && row[1] >= 0 && row[1] < 2)
          u[static_cast<unsigned int>(row[1])] = row[3];
      }
    return u;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  using tissuefem_tests::check;

  const auto &kinds = forces::ContributionRegistry<1>::instance().all();
  check(kinds.count("obstacle contact") && kinds.count("self contact")
          && kinds.count("end spring"),
        "the library's kinds and the test's are registered");

  for (const double k : {0., 1., 3.})
    {
      write_scene(k);
      std::filesystem::remove_all("results");
      const std::string name = "k = " + std::to_string(int(k));
      {
        ParameterHandler prm;
        declare_all_parameters(prm);
        prm.parse_input("scene.prm");
        const Scene<1> scene(prm);
        bool           noted = false;
        for (const auto &line : scene.notes)
          noted = noted || line.rfind("end spring k = ", 0) == 0;
        check(scene.contributions.count("end spring") == (k > 0 ? 1u : 0u)
                && noted == (k > 0),
              name
                + ": the scene creates the spring, with its note, only "
                  "when asked");
      }
      const int status            = tissuefem_tests::run_program({"scene.prm"});
      const std::vector<double> u = final_probes();
      const double              end = 0.1 / (1 + k);
      check(status == 0 && std::abs(u[1] - end) < 1e-10 * end
              && std::abs(u[0] - end / 2) < 1e-10 * end,
            name + ": u(1) = 0.1 / (1 + k), u(1/2) = u(1) / 2",
            "u(1/2) = " + std::to_string(u[0])
              + ", u(1) = " + std::to_string(u[1]));
    }
  return tissuefem_tests::exit_status();
}
