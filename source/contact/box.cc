#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/contact/box.h>

#include <array>
#include <cmath>

namespace tissuefem::contact
{
  template <int dim>
  void
  Box<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("box");
    prm.declare_entry("Centre",
                      "0, 0, 0",
                      Patterns::Anything(),
                      "The box's centre (length units; the first dim "
                      "coordinates are used).");
    prm.declare_entry("Half lengths",
                      "0.5, 0.5, 0.5",
                      Patterns::Anything(),
                      "Half its extent along each of its axes (length "
                      "units, each > 0; the first dim are used).");
    prm.declare_entry("Rotation angle",
                      "0",
                      Patterns::Double(-360, 360),
                      "The box's axes are the scene's turned by this angle "
                      "(degrees, counterclockwise) about 'Rotation axis' "
                      "(in 2D about the normal of the plane); 0 is an "
                      "axis-aligned box.");
    prm.declare_entry("Rotation axis",
                      "0, 0, 1",
                      Patterns::Anything(),
                      "3D: the axis of the rotation (any length but 0).");
    prm.leave_subsection();
  }


  template <int dim>
  Box<dim>::Box(ParameterHandler &prm)
  {
    prm.enter_subsection("box");
    centre = parse_leading_point<dim>(prm.get("Centre"), "box/Centre");
    const Point<dim> lengths
      = parse_leading_point<dim>(prm.get("Half lengths"), "box/Half lengths");
    const double   angle = prm.get_double("Rotation angle") * M_PI / 180;
    const Point<3> axis
      = parse_leading_point<3>(prm.get("Rotation axis"), "box/Rotation axis");
    prm.leave_subsection();
    for (unsigned int d = 0; d < dim; ++d)
      {
        require(lengths[d] > 0, "box/Half lengths", "must all be positive");
        half[d] = lengths[d];
      }
    rotation = unit_symmetric_tensor<dim>();
    if constexpr (dim == 2)
      {
        rotation[0][0] = rotation[1][1] = std::cos(angle);
        rotation[1][0]                  = std::sin(angle);
        rotation[0][1]                  = -std::sin(angle);
      }
    if constexpr (dim == 3)
      {
        require(axis.norm() > 0, "box/Rotation axis", "must not be zero");
        // Rodrigues: R = cos I + sin [k]x + (1 - cos) k (x) k.
        const Tensor<1, 3> k = axis / axis.norm();
        Tensor<2, 3>       cross;
        cross[0][1] = -k[2], cross[0][2] = k[1], cross[1][0] = k[2];
        cross[1][2] = -k[0], cross[2][0] = -k[1], cross[2][1] = k[0];
        rotation = std::cos(angle) * unit_symmetric_tensor<3>()
                   + std::sin(angle) * cross
                   + (1 - std::cos(angle)) * outer_product(k, k);
      }
  }


  template <int dim>
  Gap<dim>
  Box<dim>::gap(const Point<dim> &y) const
  {
    const Tensor<1, dim> q = transpose(rotation) * (y - centre);
    Tensor<1, dim>       w, sign;
    Tensor<2, dim>       exceeded;
    unsigned int         nearest = 0;
    for (unsigned int d = 0; d < dim; ++d)
      {
        sign[d]        = q[d] < 0 ? -1. : 1.;
        const double e = std::abs(q[d]) - half[d];
        if (e > 0)
          {
            w[d]           = sign[d] * e;
            exceeded[d][d] = 1;
          }
        if (e > std::abs(q[nearest]) - half[nearest])
          nearest = d;
      }
    Gap<dim>     result;
    const double outside = w.norm();
    if (outside > 0)
      {
        const Tensor<1, dim> n = w / outside;
        result.distance        = outside;
        result.normal          = rotation * n;
        result.normal_gradient = rotation * (exceeded - outer_product(n, n))
                                 * transpose(rotation) / outside;
        return result;
      }
    // Inside or on the surface: the nearest face.
    result.distance = std::abs(q[nearest]) - half[nearest];
    Tensor<1, dim> n;
    n[nearest]    = sign[nearest];
    result.normal = rotation * n;
    return result;
  }


  template <int dim>
  Drawing<dim>
  Box<dim>::drawing(const Point<dim> &, const double) const
  {
    Drawing<dim> result;
    if constexpr (dim >= 2)
      {
        // Corner k has the sign of bit d of k in axis d.
        for (unsigned int k = 0; k < (1u << dim); ++k)
          {
            Tensor<1, dim> q;
            for (unsigned int d = 0; d < dim; ++d)
              q[d] = (k >> d & 1) ? half[d] : -half[d];
            result.vertices.push_back(centre + rotation * q);
          }
        if constexpr (dim == 2)
          result.triangles = {0, 1, 3, 0, 3, 2};
        else
          // Two triangles per face, each face's corners in a cycle.
          for (const auto &face : {std::array<unsigned int, 4>{{0, 2, 3, 1}},
                                   {{4, 5, 7, 6}},
                                   {{0, 1, 5, 4}},
                                   {{2, 6, 7, 3}},
                                   {{0, 4, 6, 2}},
                                   {{1, 3, 7, 5}}})
            result.triangles.insert(
              result.triangles.end(),
              {face[0], face[1], face[2], face[0], face[2], face[3]});
        drawing::orient_outwards(result);
      }
    return result;
  }


  template class Box<1>;
  template class Box<2>;
  template class Box<3>;

  TISSUEFEM_REGISTER_SHAPE(
    Box,
    "box",
    "a rectangular block, axis-aligned or rotated (a retractor's blade, a "
    "tray).")
} // namespace tissuefem::contact
