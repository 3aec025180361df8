// The generated box: an interval, rectangle or box, optionally mapped onto
// a general quadrilateral or hexahedron.
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/geometry/source.h>

#include <array>
#include <cmath>

namespace tissuefem::geometry
{
  template <int dim>
  std::pair<Point<dim>, Point<dim>>
  box_corners(const GeometryParameters &parameters)
  {
    return {parse_leading_point<dim>(parameters.lower_corner,
                                     "Geometry/Lower corner"),
            parse_leading_point<dim>(parameters.upper_corner,
                                     "Geometry/Upper corner")};
  }

  template std::pair<Point<1>, Point<1>>
  box_corners<1>(const GeometryParameters &);
  template std::pair<Point<2>, Point<2>>
  box_corners<2>(const GeometryParameters &);
  template std::pair<Point<3>, Point<3>>
  box_corners<3>(const GeometryParameters &);


  namespace
  {
    /**
     * The box [lower, upper] in @p repetitions hexahedra per direction,
     * each cut into six tetrahedra around its diagonal from the lower to
     * the upper corner (Kuhn's split): the tetrahedron of a permutation
     * (a, b, c) of the directions steps from the lower corner along a,
     * then b, then c. Every cell is cut alike, so neighbours share their
     * faces' diagonals and the mesh is conforming.
     */
    template <int dim>
    void
    six_tetrahedra_box(const std::vector<unsigned int> &repetitions,
                       const Point<dim>                &lower,
                       const Point<dim>                &upper,
                       Triangulation<dim>              &triangulation)
    {
      if constexpr (dim == 3)
        {
          const unsigned int nx = repetitions[0] + 1, ny = repetitions[1] + 1,
                             nz = repetitions[2] + 1;
          std::vector<Point<3>> vertices;
          vertices.reserve(nx * ny * nz);
          for (unsigned int k = 0; k < nz; ++k)
            for (unsigned int j = 0; j < ny; ++j)
              for (unsigned int i = 0; i < nx; ++i)
                vertices.emplace_back(
                  lower[0] + (upper[0] - lower[0]) * i / repetitions[0],
                  lower[1] + (upper[1] - lower[1]) * j / repetitions[1],
                  lower[2] + (upper[2] - lower[2]) * k / repetitions[2]);
          const auto index = [&](const std::array<unsigned int, 3> &c) {
            return c[0] + nx * (c[1] + ny * c[2]);
          };
          const unsigned int order[6][3] = {
            {0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
          std::vector<CellData<3>> cells;
          cells.reserve(6 * repetitions[0] * repetitions[1] * repetitions[2]);
          for (unsigned int k = 0; k + 1 < nz; ++k)
            for (unsigned int j = 0; j + 1 < ny; ++j)
              for (unsigned int i = 0; i + 1 < nx; ++i)
                for (const auto &steps : order)
                  {
                    CellData<3>                 cell(4);
                    std::array<unsigned int, 3> at = {{i, j, k}};
                    cell.vertices[0]               = index(at);
                    for (unsigned int s = 0; s < 3; ++s)
                      {
                        ++at[steps[s]];
                        cell.vertices[s + 1] = index(at);
                      }
                    // deal.II's tetrahedra have positive volume; odd
                    // permutations give the other orientation.
                    const Tensor<1, 3> e1
                      = vertices[cell.vertices[1]] - vertices[cell.vertices[0]],
                      e2
                      = vertices[cell.vertices[2]] - vertices[cell.vertices[0]],
                      e3
                      = vertices[cell.vertices[3]] - vertices[cell.vertices[0]];
                    if (scalar_product(e1, cross_product_3d(e2, e3)) < 0)
                      std::swap(cell.vertices[1], cell.vertices[2]);
                    cells.push_back(cell);
                  }
          triangulation.create_triangulation(vertices, cells, SubCellData());
        }
      else
        {
          (void)repetitions;
          (void)lower;
          (void)upper;
          (void)triangulation;
          Assert(false, ExcInternalError());
        }
    }


    /// Maps the box [lower, upper] onto the cell spanned by 'Corners' with
    /// the multilinear map of deal.II's reference cell.
    template <int dim>
    void
    map_onto_corners(const GeometryParameters &parameters,
                     const Point<dim>         &lower,
                     const Point<dim>         &upper,
                     Triangulation<dim>       &triangulation)
    {
      const std::string             parameter = "Geometry/Corners";
      const std::vector<Point<dim>> corners
        = parse_points<dim>(parameters.corners, parameter);
      require(corners.size() == (1u << dim),
              parameter,
              "needs " + std::to_string(1u << dim) + " points separated by "
                + "';', got " + std::to_string(corners.size()));
      const auto map = [&](const Point<dim> &x) {
        Point<dim> result;
        for (unsigned int v = 0; v < corners.size(); ++v)
          {
            double weight = 1;
            for (unsigned int d = 0; d < dim; ++d)
              {
                const double xi = (x[d] - lower[d]) / (upper[d] - lower[d]);
                weight *= (v >> d) & 1 ? xi : 1 - xi;
              }
            result += weight * corners[v];
          }
        return result;
      };
      GridTools::transform(map, triangulation);
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->measure() <= 0)
          throw InputError(
            "Parameter 'Geometry/Corners': mapped cell "
            + std::to_string(cell->active_cell_index())
            + " has no positive volume (list the corners in deal.II's vertex "
              "order: x fastest, then y, then z)");
    }

    /// Moves the vertices toward 'Graded toward' (c): each point's
    /// normalized offset s (s_d = (x_d - c_d) over the distance from c_d
    /// to the box's face on that side) is scaled by G(rho) / rho, rho =
    /// max |s_d|, G(rho) = (rho + b rho^3) / (1 + b). G(1) = 1 keeps the
    /// faces in place, planes through c stay planes (the symmetry faces of
    /// a quarter model), and rho G'(rho) / G(rho) <= 3 bounds each cell's
    /// stretch between the radial and tangential directions.
    template <int dim>
    void
    grade(const GeometryParameters &parameters,
          const Point<dim>         &lower,
          const Point<dim>         &upper,
          Triangulation<dim>       &triangulation)
    {
      if (parameters.grading == 1)
        return;
      const Point<dim> c
        = Utilities::trim(parameters.graded_toward).empty()
            ? lower
            : parse_leading_point<dim>(parameters.graded_toward,
                                       "Geometry/Graded toward");
      for (unsigned int d = 0; d < dim; ++d)
        require(c[d] >= lower[d] && c[d] <= upper[d],
                "Geometry/Graded toward",
                "must lie in the box");
      const double b = parameters.grading - 1;
      GridTools::transform(
        [&](const Point<dim> &x) {
          Tensor<1, dim> s, side;
          double         rho = 0;
          for (unsigned int d = 0; d < dim; ++d)
            {
              side[d] = x[d] >= c[d] ? upper[d] - c[d] : c[d] - lower[d];
              s[d]    = side[d] > 0 ? (x[d] - c[d]) / side[d] : 0;
              rho     = std::max(rho, std::abs(s[d]));
            }
          if (rho == 0)
            return x;
          const double scale = (1 + b * rho * rho) / (1 + b);
          Point<dim>   result;
          for (unsigned int d = 0; d < dim; ++d)
            result[d] = c[d] + scale * s[d] * side[d];
          return result;
        },
        triangulation);
    }
  } // namespace


  /**
   * 'Lower corner' to 'Upper corner' in 'Subdivisions' cells per direction,
   * of 'Cell type', graded toward a point by 'Grading'; boundary ids 0/1 on the
   * faces x = lower/upper, 2/3 on y, 4/5 on z, material id 0; mapped onto
   * 'Corners' if given.
   */
  template <int dim>
  class Box : public Source<dim>
  {
  public:
    void
    build(const GeometryParameters &parameters,
          Triangulation<dim>       &triangulation) const override
    {
      const auto [lower, upper] = box_corners<dim>(parameters);
      for (unsigned int d = 0; d < dim; ++d)
        require(upper[d] > lower[d],
                "Geometry/Upper corner",
                "must exceed 'Lower corner' in every coordinate");

      const std::vector<std::string> pieces
        = Utilities::split_string_list(parameters.subdivisions);
      require(pieces.size() >= dim,
              "Geometry/Subdivisions",
              "needs " + std::to_string(dim) + " values");
      std::vector<unsigned int> repetitions(dim);
      for (unsigned int d = 0; d < dim; ++d)
        repetitions[d] = Utilities::string_to_int(pieces[d]);

      if (parameters.cell_type == "simplex" && dim > 1)
        {
          // deal.II 9.4 cannot colorize simplex boxes; give the faces the
          // same ids a colorized hypercube box has.
          if (dim == 3 && parameters.tetrahedra_per_hexahedron == 6)
            six_tetrahedra_box(repetitions, lower, upper, triangulation);
          else
            GridGenerator::subdivided_hyper_rectangle_with_simplices(
              triangulation, repetitions, lower, upper);
          const double tolerance = 1e-10 * lower.distance(upper);
          for (const auto &cell : triangulation.active_cell_iterators())
            for (const auto &face : cell->face_iterators())
              if (face->at_boundary())
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    if (std::abs(face->center()[d] - lower[d]) < tolerance)
                      face->set_boundary_id(2 * d);
                    if (std::abs(face->center()[d] - upper[d]) < tolerance)
                      face->set_boundary_id(2 * d + 1);
                  }
        }
      else
        {
          GridGenerator::subdivided_hyper_rectangle(
            triangulation, repetitions, lower, upper, /*colorize=*/true);
          // Colorizing also numbers the cells' material ids by octant;
          // generated boxes are one material unless predicates say else.
          for (const auto &cell : triangulation.active_cell_iterators())
            cell->set_material_id(0);
        }
      grade(parameters, lower, upper, triangulation);
      if (!Utilities::trim(parameters.corners).empty())
        map_onto_corners(parameters, lower, upper, triangulation);
    }

    bool
    faces_carry_ids() const override
    {
      return true;
    }
  };
} // namespace tissuefem::geometry

namespace
{
  using tissuefem::geometry::Box;
}
TISSUEFEM_REGISTER_GEOMETRY_SOURCE(
  Box,
  "box",
  "an interval, rectangle or box from 'Lower corner', 'Upper corner', "
  "'Subdivisions' and 'Cell type' (boundary ids 0/1 on x = lower/upper, 2/3 "
  "on y, 4/5 on z), optionally mapped onto 'Corners'.")
