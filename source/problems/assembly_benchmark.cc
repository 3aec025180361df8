#include <deal.II/base/function_lib.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/utilities.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/numerics/vector_tools.h>

#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/boundary/boundary_conditions.h>
#include <tissuefem/geometry/geometry.h>
#include <tissuefem/materials/material_set.h>
#include <tissuefem/problems/floor_kernel.h>
#include <tissuefem/problems/interface.h>
#include <tissuefem/problems/neo_hookean_floor.h>
#include <tissuefem/scene/scene.h>
#include <tissuefem/solid/discretization.h>
#include <tissuefem/solid/solid.h>

#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>

namespace tissuefem::problems
{
  /**
   * Times the assembly of the Jacobian and residual of the same deformed
   * state with each tangent method, on a hexahedral (Q1) and a tetrahedral
   * (P1) box, and prints microseconds per cell, the ratio to the hand-coded
   * tangent, and how far each method's matrix is from the hand-coded one.
   * All timings come from one run, so their ratios are meaningful on a
   * noisy machine; each figure is the fastest of 'Repetitions' runs.
   */
  template <int dim>
  class AssemblyBenchmark : public Interface
  {
  public:
    AssemblyBenchmark(ParameterHandler &prm, const RunContext &);

    static void
    declare_parameters(ParameterHandler &prm);

    void
    setup() override
    {
    }

    void
    run() override;

  private:
    ParameterHandler             &prm;
    materials::MaterialParameters material_parameters;
    std::string                   hexahedra, tetrahedra, mesh_file;
    unsigned int                  repetitions;
    /// The targets the report measures against (0: none).
    struct Targets
    {
      double update_ms = 0, tangent_us = 0, floor_ratio = 0;
    } targets;

    /// A generated box of @p cell_type with @p subdivisions.
    void
    benchmark_box(const std::string &cell_type,
                  const std::string &subdivisions) const;
    /// The scene of this file with the 'Geometry' entries @p geometry
    /// (name, value) set.
    void
    benchmark_mesh(
      const std::vector<std::pair<std::string, std::string>> &geometry,
      const std::string                                      &label) const;

    /// Times internal-force assembly, residual only and with the Jacobian,
    /// of the floor kernel and of tissuefem with 1 and all threads.
    void
    compare_with_floor(solid::Discretization<dim>        &discretization,
                       boundary::BoundaryConditions<dim> &boundary_conditions,
                       const VectorType                  &u) const;
  };


  template <int dim>
  void
  AssemblyBenchmark<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Assembly benchmark");
    prm.declare_entry("Hexahedra subdivisions",
                      "22, 22, 21",
                      Patterns::List(Patterns::Integer(1, 1000)),
                      "Cells per direction of the unit box meshed with "
                      "quadrilaterals/hexahedra; empty to skip.");
    prm.declare_entry("Simplex subdivisions",
                      "13, 13, 12",
                      Patterns::List(Patterns::Integer(1, 1000)),
                      "Boxes per direction of the unit box whose boxes are "
                      "split into triangles/tetrahedra; empty to skip.");
    prm.declare_entry("Mesh file",
                      "",
                      Patterns::Anything(),
                      "A mesh file (any format 'Geometry/Mesh file' reads; "
                      "relative to this parameter file) benchmarked as well, "
                      "e.g. meshes/jeffrey_muscle.vtu; empty to skip.");
    prm.declare_entry("Force update target",
                      "0",
                      Patterns::Double(0),
                      "Wall-clock milliseconds one internal-force update of "
                      "a whole mesh should take (0.25: 500 Hz haptics with "
                      "8x margin); with > 0, each mesh's report ends with "
                      "the measured time per update and its ratio to this. "
                      "0: no target.");
    prm.declare_entry("Forces with tangent target",
                      "0",
                      Patterns::Double(0),
                      "Wall-clock microseconds per cell the lean kernel's "
                      "forces with tangent (residual and Jacobian, added "
                      "into the matrix) should take with all threads (issue "
                      "32: 0.2 on two threads); with > 0 the report prints "
                      "the measured time against it. 0: no target.");
    prm.declare_entry("Floor ratio target",
                      "0",
                      Patterns::Double(0),
                      "The largest ratio of tissuefem's internal-force time "
                      "(residual only) to the true floor's (issue 32: 1.2); "
                      "with > 0 and a true floor in the table (neo-Hookean "
                      "on linear simplices, one process) the report prints "
                      "the measured ratios, on one thread and on all, "
                      "against it. 0: no target.");
    prm.declare_entry("Repetitions",
                      "3",
                      Patterns::Integer(1, 100),
                      "Assemblies per method; the fastest is reported.");
    prm.leave_subsection();
  }


  template <int dim>
  AssemblyBenchmark<dim>::AssemblyBenchmark(ParameterHandler &prm,
                                            const RunContext &context)
      : prm(prm)
  {
    material_parameters.parse_parameters(prm);
    prm.enter_subsection("Assembly benchmark");
    hexahedra           = prm.get("Hexahedra subdivisions");
    tetrahedra          = prm.get("Simplex subdivisions");
    repetitions         = prm.get_integer("Repetitions");
    mesh_file           = Utilities::trim(prm.get("Mesh file"));
    targets.update_ms   = prm.get_double("Force update target");
    targets.tangent_us  = prm.get_double("Forces with tangent target");
    targets.floor_ratio = prm.get_double("Floor ratio target");
    prm.leave_subsection();
    // Relative to the parameter file (which may be in the working
    // directory: then the parameter directory is empty).
    if (!mesh_file.empty())
      mesh_file
        = (std::filesystem::path(context.parameter_directory) / mesh_file)
            .string();
  }


  template <int dim>
  void
  AssemblyBenchmark<dim>::benchmark_box(const std::string &cell_type,
                                        const std::string &subdivisions) const
  {
    benchmark_mesh({{"Source", "box"},
                    {"Cell type", cell_type},
                    {"Lower corner", "0, 0, 0"},
                    {"Upper corner", "1, 1, 1"},
                    {"Subdivisions", subdivisions},
                    {"Scale", "1"},
                    {"Global refinements", "0"}},
                   cell_type == "simplex" ? "P1 simplices" : "Q1 hypercubes");
  }


  template <int dim>
  void
  AssemblyBenchmark<dim>::benchmark_mesh(
    const std::vector<std::pair<std::string, std::string>> &geometry,
    const std::string                                      &label) const
  {
    // The mesh, discretization and boundary conditions a run of this file
    // would build; the benchmark then assembles with its own materials.
    prm.enter_subsection("Geometry");
    for (const auto &[name, value] : geometry)
      prm.set(name, value);
    prm.leave_subsection();
    Scene<dim>  scene(prm);
    const auto &triangulation       = scene.triangulation;
    auto       &discretization      = *scene.discretization;
    auto       &boundary_conditions = *scene.boundary_conditions;

    // A smooth, finite deformation: stretches, shears and a twist.
    VectorType u;
    discretization.initialize_vector(u);
    {
      static const char *deformations[]
        = {"0.2*x*x",
           "0.2*x*y + 0.1*sin(3*y); 0.1*x - 0.15*y*y",
           "0.2*x*y + 0.1*sin(3*z); 0.1*x - 0.15*y*z; 0.05*x*x - 0.1*z"};
      auto deformation = make_function<dim>(deformations[dim - 1],
                                            dim,
                                            "benchmark deformation");
      VectorTools::interpolate(*discretization.mapping,
                               discretization.dof_handler,
                               *deformation,
                               u);
    }
    VectorType u_tilde;
    discretization.initialize_vector(u_tilde);

    parallel_tools::screen()
      << "\n"
      << label << ": " << triangulation.n_global_active_cells() << " cells, "
      << u.size() << " unknowns, model '" << material_parameters.model_names[0]
      << "'\n"
      << std::setw(32) << "tangent" << std::setw(14) << "us per cell"
      << std::setw(16) << "ratio to first" << std::setw(34)
      << "max|K - K_first| / max|K_first|"
      << "\n";

    std::vector<std::pair<std::string, materials::TangentMethod>> methods
      = {{"automatic differentiation",
          materials::TangentMethod::automatic_differentiation},
         {"automatic differentiation in F",
          materials::TangentMethod::automatic_differentiation_in_F},
         {"deal.II AD helper", materials::TangentMethod::dealii_ad_helper}};
    {
      materials::MaterialParameters parameters = material_parameters;
      materials::MaterialSet<dim>   probe(parameters, prm);
      if (probe.material(0).has_hand_coded_tangent())
        methods.insert(methods.begin(),
                       {"hand coded", materials::TangentMethod::hand_coded});
    }

    double     hand_time = 0;
    MatrixType reference;
    for (const auto &[name, method] : methods)
      {
        materials::MaterialParameters parameters = material_parameters;
        parameters.tangent_method                = method;
        materials::MaterialSet<dim> materials(parameters, prm);
        solid::Solid<dim>           system(
          discretization,
          materials,
          boundary_conditions,
          solid::formulations::create<dim>(materials.formulation(), prm));
        VectorType residual;
        double     best = 1e300;
        for (unsigned int r = 0; r < repetitions; ++r)
          {
            const auto start = std::chrono::steady_clock::now();
            system.implicit_residual(u, u_tilde, 1., 0., residual, true);
            best = std::min(best,
                            std::chrono::duration<double>(
                              std::chrono::steady_clock::now() - start)
                              .count());
          }
        const double per_cell
          = 1e6 * best / triangulation.n_global_active_cells();
        double difference = 0;
        if (&method == &methods.front().second)
          {
            hand_time = per_cell;
            reference.copy_from(system.jacobian());
          }
        else
          {
            MatrixType diff;
            diff.copy_from(system.jacobian());
            diff.add(-1., reference);
            difference = diff.linfty_norm() / reference.linfty_norm();
          }
        parallel_tools::screen()
          << std::setw(32) << name << std::fixed << std::setprecision(2)
          << std::setw(14) << per_cell << std::setw(16) << per_cell / hand_time
          << std::scientific << std::setprecision(1) << std::setw(34)
          << difference << std::defaultfloat << std::setprecision(6) << "\n";
      }
    compare_with_floor(discretization, boundary_conditions, u);
  }


  namespace
  {
    /// One line of the floor comparison: microseconds per cell.
    struct FloorRow
    {
      std::string name;
      double      residual, jacobian;
    };

    /// Microseconds per cell of the whole mesh (@p n_cells) that @p work
    /// takes: the slowest process's best wall time over the repetitions,
    /// divided by all cells.
    template <typename Work>
    double
    time_per_cell(const Work        &work,
                  const unsigned int repetitions,
                  const double       n_cells)
    {
      double best = 1e300;
      for (unsigned int r = 0; r < repetitions; ++r)
        {
          MPI_Barrier(parallel_tools::communicator());
          const auto start = std::chrono::steady_clock::now();
          work();
          MPI_Barrier(parallel_tools::communicator());
          best = std::min(best,
                          std::chrono::duration<double>(
                            std::chrono::steady_clock::now() - start)
                            .count());
        }
      return 1e6 * Utilities::MPI::max(best, parallel_tools::communicator())
             / n_cells;
    }

    /// max_i |a_i - b_i| and max_i |b_i| over the locally owned entries.
    template <typename VectorA, typename VectorB>
    std::pair<double, double>
    largest_difference(const IndexSet &owned,
                       const VectorA  &a,
                       const VectorB  &b)
    {
      double difference = 0, largest = 0;
      for (const auto i : owned)
        {
          difference = std::max(difference, std::abs(a[i] - b[i]));
          largest    = std::max(largest, std::abs(b[i]));
        }
      return {difference, largest};
    }

    /// The table of compare_with_floor(): each row's times and their
    /// ratios to the first row's, and the measured update against the
    /// target. @p difference is the quadrature-loop kernel's relative
    /// difference, @p floor_difference the fused kernel's (< 0: none).
    void
    print_floor_table(const std::vector<FloorRow> &rows,
                      const double                 floor_difference,
                      const double                 difference,
                      const double                 n_cells,
                      const unsigned int           all_threads,
                      const std::size_t            all_thread_row,
                      const double                 target_ms)
    {
      auto &screen = parallel_tools::screen();
      if (floor_difference >= 0)
        screen << "True floor: forces differ from tissuefem's by "
               << std::scientific << std::setprecision(1) << floor_difference
               << " relative" << std::defaultfloat << std::setprecision(6)
               << "\n";
      screen << "Against the first kernel (internal forces only; "
             << parallel_tools::n_processes()
             << " MPI process(es); us per cell "
             << "of the whole mesh; ";
      if (parallel_tools::n_processes() == 1)
        screen << "the quadrature-loop kernel's residual differs from "
                  "tissuefem's by "
               << std::scientific << std::setprecision(1) << difference
               << " relative):\n";
      else
        screen << "each process's single-thread kernels sum only its own "
                  "cells):\n";
      screen << std::defaultfloat << std::setw(42) << "" << std::setw(14)
             << "residual" << std::setw(10) << "ratio" << std::setw(22)
             << "residual + Jacobian" << std::setw(10) << "ratio"
             << "\n";
      for (const auto &row : rows)
        screen << std::setw(42) << row.name << std::fixed
               << std::setprecision(2) << std::setw(14) << row.residual
               << std::setw(10) << row.residual / rows[0].residual
               << std::setw(22) << row.jacobian << std::setw(10)
               << row.jacobian / rows[0].jacobian << std::defaultfloat
               << std::setprecision(6) << "\n";
      if (target_ms > 0)
        {
          const double update_ms
            = rows[all_thread_row].residual * n_cells / 1e3;
          screen << "One internal-force update of the whole mesh (" << n_cells
                 << " cells): " << std::setprecision(3) << update_ms
                 << " ms with " << all_threads << " thread(s) (" << rows[0].name
                 << ": " << rows[0].residual * n_cells / 1e3 << " ms); target "
                 << target_ms
                 << " ms: measured / target = " << update_ms / target_ms
                 << std::setprecision(6) << "\n";
        }
    }

    /// The kernel targets after the table: the forces with tangent per
    /// cell with all threads, and (with a true floor, the first row) the
    /// forces' ratio to the floor on one thread and on all; tissuefem's
    /// rows are @p one_thread_row and @p all_thread_row.
    void
    print_targets(const std::vector<FloorRow> &rows,
                  const bool                   has_floor,
                  const unsigned int           all_threads,
                  const std::size_t            one_thread_row,
                  const std::size_t            all_thread_row,
                  const double                 tangent_us,
                  const double                 floor_ratio)
    {
      auto &screen = parallel_tools::screen();
      screen << std::setprecision(3);
      if (tangent_us > 0)
        screen << "Forces with tangent, added into the matrix, " << all_threads
               << " thread(s): " << rows[all_thread_row].jacobian
               << " us per cell; target " << tangent_us
               << " us: measured / target = "
               << rows[all_thread_row].jacobian / tangent_us << "\n";
      if (floor_ratio > 0 && has_floor)
        {
          const double one = rows[one_thread_row].residual / rows[0].residual;
          const double all = rows[all_thread_row].residual / rows[0].residual;
          screen << "Forces against the true floor (time ratio): " << one
                 << " on 1 thread, " << all << " on " << all_threads
                 << " thread(s); target " << floor_ratio
                 << ": measured / target = " << one / floor_ratio << " and "
                 << all / floor_ratio << "\n";
        }
      screen << std::setprecision(6);
    }
  } // namespace


  template <int dim>
  void
  AssemblyBenchmark<dim>::compare_with_floor(
    solid::Discretization<dim>        &discretization,
    boundary::BoundaryConditions<dim> &boundary_conditions,
    const VectorType                  &u) const
  {
    const double n_cells
      = dynamic_cast<const parallel::TriangulationBase<dim> &>(
          discretization.dof_handler.get_triangulation())
          .n_global_active_cells();
    materials::MaterialSet<dim> materials(material_parameters, prm);
    solid::Solid<dim>           solid(
      discretization,
      materials,
      boundary_conditions,
      solid::formulations::create<dim>(materials.formulation(), prm));
    FloorKernel<dim>     floor(discretization, materials);
    const Vector<double> u_all(u);
    auto                 time = [&](const auto &work) {
      return time_per_cell(work, repetitions, n_cells);
    };
    VectorType residual, zero;
    discretization.initialize_vector(zero);
    const unsigned int all_threads = MultithreadInfo::n_threads();

    std::vector<FloorRow> rows;
    // The true floor where it exists: the fused neo-Hookean kernel of
    // linear simplices (neo_hookean_floor.h).
    double floor_difference = -1;
    if constexpr (dim > 1)
      if (material_parameters.model_names[0] == "neo-Hookean"
          && discretization.simplex && discretization.fe->degree == 1
          && material_parameters.model_names.size() == 1
          && parallel_tools::n_processes() == 1)
        {
          NeoHookeanFloor<dim> fused(discretization,
                                     material_parameters.constants[0]);
          rows.push_back({"true floor: fused neo-Hookean (1 thread)",
                          time([&] { fused.assemble(u_all, false); }),
                          time([&] { fused.assemble(u_all, true); })});
          solid.internal_force(u, residual);
          const auto [difference, largest]
            = largest_difference(discretization.locally_owned,
                                 residual,
                                 fused.residual());
          floor_difference = difference / largest;
        }
    rows.push_back({"quadrature-loop kernel (1 thread)",
                    time([&] { floor.assemble(u_all, false); }),
                    time([&] { floor.assemble(u_all, true); })});
    const std::size_t one_thread_row = rows.size();
    for (const unsigned int threads : {1u, all_threads})
      {
        MultithreadInfo::set_thread_limit(threads);
        rows.push_back(
          {"tissuefem, " + std::to_string(threads) + " thread(s)",
           time([&] { solid.internal_force(u, residual); }),
           time([&] {
             solid.implicit_residual(u, zero, 0., 0., residual, true);
           })});
        if (threads == all_threads)
          break;
      }
    MultithreadInfo::set_thread_limit(all_threads);
    const std::size_t all_thread_row = rows.size() - 1;
    if (solid.lean_kernel_active())
      {
        // The general quadrature loop on the same mesh, for the ratio the
        // lean kernel of linear simplices buys.
        discretization.lean_kernel = false;
        solid::Solid<dim> general(
          discretization,
          materials,
          boundary_conditions,
          solid::formulations::create<dim>(materials.formulation(), prm));
        rows.push_back(
          {"general path, " + std::to_string(all_threads) + " thread(s)",
           time([&] { general.internal_force(u, residual); }),
           time([&] {
             general.implicit_residual(u, zero, 0., 0., residual, true);
           })});
        discretization.lean_kernel = true;
        solid.setup();
      }

    // The same numbers: f_int of both, relative to its largest entry.
    solid.internal_force(u, residual);
    auto [difference, largest]
      = largest_difference(discretization.locally_owned,
                           residual,
                           floor.residual());
    difference
      = Utilities::MPI::max(difference, parallel_tools::communicator());
    largest = Utilities::MPI::max(largest, parallel_tools::communicator());
    print_floor_table(rows,
                      floor_difference,
                      difference / largest,
                      n_cells,
                      all_threads,
                      all_thread_row,
                      targets.update_ms);
    print_targets(rows,
                  floor_difference >= 0,
                  all_threads,
                  one_thread_row,
                  all_thread_row,
                  targets.tangent_us,
                  targets.floor_ratio);
  }


  template <int dim>
  void
  AssemblyBenchmark<dim>::run()
  {
    parallel_tools::screen()
      << "Assembly benchmark: Jacobian + residual of one deformed "
         "state, fastest of "
      << repetitions << " runs (wall time; ratios are the figure of "
      << "merit)." << std::endl;
    if (!Utilities::trim(hexahedra).empty())
      benchmark_box("hypercube", hexahedra);
    if (!Utilities::trim(tetrahedra).empty())
      benchmark_box("simplex", tetrahedra);
    if (!mesh_file.empty())
      {
        benchmark_mesh({{"Source", "file"},
                        {"Mesh file", mesh_file},
                        {"Scale", "1"},
                        {"Global refinements", "0"}},
                       "mesh file " + mesh_file);
      }
  }

  template class AssemblyBenchmark<1>;
  template class AssemblyBenchmark<2>;
  template class AssemblyBenchmark<3>;

  TISSUEFEM_REGISTER_PROBLEM(AssemblyBenchmark,
                             "assembly benchmark",
                             "times Jacobian assembly with each tangent "
                             "method on a hexahedral and a tetrahedral box.")
} // namespace tissuefem::problems
