#include <deal.II/base/function_parser.h>
#include <deal.II/grid/grid_generator.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/geometry/geometry.h>
#include <tissuefem/geometry/source.h>

#include <filesystem>
#include <map>
#include <sstream>

namespace tissuefem::geometry
{
  void
  GeometryParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    {
      // The choices are the registered sources (geometry/source.h), one
      // file each.
      const auto &sources = SourceRegistry<2>::instance();
      prm.declare_entry("Source",
                        "box",
                        Patterns::Selection(sources.selection_pattern()),
                        sources.documentation());
      prm.declare_entry("Cell type",
                        "hypercube",
                        Patterns::Selection("hypercube|simplex"),
                        "For 'box': quadrilaterals/hexahedra or "
                        "triangles/tetrahedra (ignored in 1D and for files, "
                        "whose cells are what the file holds).");
      prm.declare_entry("Lower corner",
                        "0, 0, 0",
                        Patterns::Anything(),
                        "For 'box': the lower corner, 'x, y, z' (only the "
                        "first Dimension coordinates are read), length units.");
      prm.declare_entry("Upper corner",
                        "1, 1, 1",
                        Patterns::Anything(),
                        "For 'box': the upper corner, as 'Lower corner'.");
      prm.declare_entry("Subdivisions",
                        "1, 1, 1",
                        Patterns::List(Patterns::Integer(1, 10000)),
                        "For 'box': cells per direction before refinement "
                        "(only the first Dimension values are read).");
      prm.declare_entry(
        "Tetrahedra per hexahedron",
        "5",
        Patterns::Integer(5, 6),
        "For 'box' with 'Cell type = simplex' in 3D: how each hexahedron of "
        "the grid is cut. 5: deal.II's split (a central tetrahedron and four "
        "corners, alternating between neighbours so that the faces match). "
        "6: six tetrahedra around the diagonal from each cell's lower to its "
        "upper corner (Kuhn's split; the same in every cell, so that the "
        "faces match), the split of SOFA's benchmark beams: a grid of 75 x "
        "15 x 15 cells gives their 101,250 tetrahedra. Ignored in 2D (two "
        "triangles per quadrilateral).");
      prm.declare_entry(
        "Grading",
        "1",
        Patterns::Double(1, 1e6),
        "For 'box': how many times smaller than evenly spaced the cells are "
        "at 'Graded toward' (1: evenly spaced). The cells grow away from "
        "that point in shells (cube surfaces around it): a shell at "
        "normalized distance rho in [0, 1] (0 at the point, 1 on the box's "
        "faces, measured in each direction relative to the point's distance "
        "to the face on that side) moves to G(rho) = (rho + b rho^3) / (1 + "
        "b), b = Grading - 1: evenly spaced near the point, growing as "
        "rho^3 away from it, so that no cell is more than three times "
        "longer than wide, and the outermost are about three times the even "
        "spacing. Grades a box finely where a load is concentrated (the "
        "Hertz scene's contact) on tetrahedra too, which deal.II 9.4 cannot "
        "refine locally.");
      prm.declare_entry("Graded toward",
                        "",
                        Patterns::Anything(),
                        "For 'box' with 'Grading' > 1: the point 'x, y, z' "
                        "(length units, in the box, best a vertex of the "
                        "evenly spaced mesh) where the cells are finest; "
                        "empty: the lower corner.");
      prm.declare_entry(
        "Corners",
        "",
        Patterns::Anything(),
        "For 'box': empty, or the 2^Dimension corners of a general "
        "quadrilateral or hexahedron, 'x, y[, z]' separated by ';', in "
        "deal.II's vertex order (x runs fastest, then y, then z): the "
        "subdivided box is mapped onto it by the multilinear map of the "
        "corners, and its faces keep the box's ids (0/1: the faces that were "
        "x = lower/upper, 2/3: y, 4/5: z). Cook's membrane is '0, 0; 48, 44; "
        "0, 44; 48, 60'.");
      prm.declare_entry("Mesh file",
                        "",
                        Patterns::Anything(),
                        "For 'file': a mesh chosen by extension: .msh (Gmsh "
                        "1.0 or 2.x ASCII), .vtk (legacy VTK), .inp (Abaqus), "
                        "all read by deal.II's GridIn, or .vtu (VTK XML "
                        "UnstructuredGrid, ASCII: tetrahedra/hexahedra, "
                        "triangles/quadrilaterals; material ids from an "
                        "integer cell array 'MaterialIds', 'material_id', "
                        "'materialID' or 'gmsh:physical', boundary ids from "
                        "the same array on face cells). A relative path is "
                        "taken relative to the parameter file's directory.");
      prm.declare_entry("Scale",
                        "1",
                        Patterns::Double(0),
                        "Factor applied to the coordinates of a mesh file, to "
                        "convert its length unit.");
      prm.declare_entry("Global refinements",
                        "0",
                        Patterns::Integer(0, 12),
                        "Uniform refinements applied after building.");
      prm.declare_entry(
        "Boundary id predicates",
        "",
        Patterns::Anything(),
        "Entries 'id: expression' separated by '|', e.g. '1: y < 0.5 | 2: x "
        "> 3'. Each boundary face whose centre (x, y, z) makes the muparser "
        "expression non-zero gets the id; later entries win. Applied after "
        "refinement. For a mesh file, faces that match no predicate keep "
        "the id the file gave them, except id 0 (which files without "
        "boundary ids give every face): those get id 254, which no "
        "predicate may name, so that a condition on id 0 acts only where a "
        "predicate (or the file) put 0. A run prints how many faces carry "
        "each id.");
      prm.declare_entry(
        "Material id predicates",
        "",
        Patterns::Anything(),
        "Entries 'id: expression' separated by '|', e.g. '1: x > 0.5'. Each "
        "cell whose centre makes the expression non-zero gets the material "
        "id (see 'Materials/Material ids'); later entries win.");
      prm.declare_entry(
        "Mesh distribution",
        "shared",
        Patterns::Selection("shared|distributed"),
        "How the mesh of the elasticity problem is spread over the MPI "
        "processes of a run (mpirun -np N); METIS gives each process the same "
        "part of the cells to assemble "
        "either way, so results agree to the linear solver's tolerance. "
        "'shared': every process holds the whole mesh (deal.II's "
        "parallel::shared::Triangulation). 'distributed': each process holds "
        "its own cells and the layer around them "
        "(parallel::fullydistributed::Triangulation), so that memory per "
        "process falls with the number of processes; the whole mesh is built "
        "and checked on every process first and freed before the unknowns "
        "are numbered. What needs every process to hold the whole mesh is "
        "refused with 'distributed', naming its parameter: adaptive "
        "refinement, the grasping tool, the live view, a numerically "
        "differenced Jacobian; and 1D bodies. A checkpoint restarts with the "
        "setting it was written with. One process: the same as 'shared'.");
    }
    prm.leave_subsection();
  }


  void
  GeometryParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    source                    = prm.get("Source");
    cell_type                 = prm.get("Cell type");
    lower_corner              = prm.get("Lower corner");
    upper_corner              = prm.get("Upper corner");
    subdivisions              = prm.get("Subdivisions");
    corners                   = prm.get("Corners");
    grading                   = prm.get_double("Grading");
    tetrahedra_per_hexahedron = prm.get_integer("Tetrahedra per hexahedron");
    graded_toward             = prm.get("Graded toward");
    mesh_file                 = prm.get("Mesh file");
    scale                     = prm.get_double("Scale");
    global_refinements        = prm.get_integer("Global refinements");
    boundary_id_predicates    = prm.get("Boundary id predicates");
    material_id_predicates    = prm.get("Material id predicates");
    distribution              = prm.get("Mesh distribution") == "distributed"
                                  ? Distribution::distributed
                                  : Distribution::shared;
    prm.leave_subsection();
    require(scale > 0, "Geometry/Scale", "must be > 0");
  }


  void
  GeometryParameters::resolve_relative_to(const std::string &directory)
  {
    const std::filesystem::path mesh(mesh_file);
    if (!mesh.empty() && mesh.is_relative())
      mesh_file = (std::filesystem::path(directory) / mesh).string();
  }


  namespace
  {
    template <int dim>
    void
    apply_boundary_predicates(const std::string  &text,
                              const bool          from_file,
                              Triangulation<dim> &triangulation)
    {
      const std::string parameter = "Geometry/Boundary id predicates";
      const auto        entries   = parse_id_entries(text, parameter);
      for (const auto &entry : entries)
        require(entry.first != unmatched_boundary_id,
                parameter,
                "id " + std::to_string(unmatched_boundary_id)
                  + " is reserved for faces no predicate matches");
      // A file without boundary ids gives every face id 0; if faces that
      // no predicate matches kept it, a condition on id 0 would silently
      // act on them too.
      if (from_file && !entries.empty())
        for (const auto &cell : triangulation.active_cell_iterators())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary() && face->boundary_id() == 0)
              face->set_boundary_id(unmatched_boundary_id);
      for (const auto &[id, expression] : entries)
        {
          const auto predicate = make_function<dim>(expression, 1, parameter);
          for (const auto &cell : triangulation.active_cell_iterators())
            for (const auto &face : cell->face_iterators())
              if (face->at_boundary() && predicate->value(face->center()) != 0)
                face->set_boundary_id(id);
        }
    }

    /// Material ids from predicates on the cell centres; later entries win.
    template <int dim>
    void
    apply_material_predicates(const std::string  &text,
                              Triangulation<dim> &triangulation)
    {
      const std::string parameter = "Geometry/Material id predicates";
      for (const auto &[id, expression] : parse_id_entries(text, parameter))
        {
          require(id < numbers::invalid_material_id,
                  parameter,
                  "material ids must be below "
                    + std::to_string(int(numbers::invalid_material_id)));
          const auto predicate = make_function<dim>(expression, 1, parameter);
          for (const auto &cell : triangulation.active_cell_iterators())
            if (predicate->value(cell->center()) != 0)
              cell->set_material_id(id);
        }
    }
  } // namespace


  template <int dim>
  void
  build_triangulation(const GeometryParameters &parameters,
                      Triangulation<dim>       &triangulation)
  {
    const auto source
      = SourceRegistry<dim>::instance().create(parameters.source);
    source->build(parameters, triangulation);
    if (parameters.global_refinements > 0
        && !triangulation.all_reference_cells_are_hyper_cube())
      {
        // deal.II 9.4 crashes refining simplices under the mesh smoothing
        // the adaptive meshes need (limit_level_difference_at_vertices):
        // refine a flat copy without smoothing and flatten it back.
        Triangulation<dim> plain;
        GridGenerator::flatten_triangulation(triangulation, plain);
        plain.refine_global(parameters.global_refinements);
        triangulation.clear();
        GridGenerator::flatten_triangulation(plain, triangulation);
      }
    else
      triangulation.refine_global(parameters.global_refinements);
    apply_boundary_predicates(parameters.boundary_id_predicates,
                              !source->faces_carry_ids(),
                              triangulation);
    apply_material_predicates(parameters.material_id_predicates, triangulation);
  }


  template <int dim>
  std::string
  describe_boundary_ids(const Triangulation<dim> &triangulation)
  {
    // Each process counts the faces of its own cells (a serial mesh: all
    // of them), whether or not it holds the others.
    std::map<types::boundary_id, unsigned int> faces;
    for (const auto &id : triangulation.get_boundary_ids())
      faces[id] = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            ++faces[face->boundary_id()];
    if (const auto *parallel_mesh
        = dynamic_cast<const parallel::TriangulationBase<dim> *>(
          &triangulation))
      for (auto &[id, count] : faces)
        count = Utilities::MPI::sum(count, parallel_mesh->get_communicator());
    std::ostringstream text;
    text << "boundary faces by id:";
    for (const auto &[id, count] : faces)
      text << ' ' << int(id) << " (" << count << ")";
    return text.str();
  }


  template <int dim>
  bool
  is_simplex_mesh(const Triangulation<dim> &triangulation)
  {
    return dim > 1 && !triangulation.all_reference_cells_are_hyper_cube();
  }

  template void
  build_triangulation<1>(const GeometryParameters &, Triangulation<1> &);
  template void
  build_triangulation<2>(const GeometryParameters &, Triangulation<2> &);
  template void
  build_triangulation<3>(const GeometryParameters &, Triangulation<3> &);
  template std::string
  describe_boundary_ids<1>(const Triangulation<1> &);
  template std::string
  describe_boundary_ids<2>(const Triangulation<2> &);
  template std::string
  describe_boundary_ids<3>(const Triangulation<3> &);
  template bool
  is_simplex_mesh<1>(const Triangulation<1> &);
  template bool
  is_simplex_mesh<2>(const Triangulation<2> &);
  template bool
  is_simplex_mesh<3>(const Triangulation<3> &);
} // namespace tissuefem::geometry
