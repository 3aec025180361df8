#include <tissuefem/contact/drawing.h>

#include <cmath>
#include <utility>

namespace tissuefem::contact::drawing
{
  std::pair<Tensor<1, 3>, Tensor<1, 3>>
  tangent_frame(const Tensor<1, 3> &axis)
  {
    // Start from the coordinate direction farthest from the axis.
    Tensor<1, 3> e;
    unsigned int least = 0;
    for (unsigned int d = 1; d < 3; ++d)
      if (std::abs(axis[d]) < std::abs(axis[least]))
        least = d;
    e[least]           = 1;
    Tensor<1, 3> first = e - (e * axis) * axis;
    first /= first.norm();
    return {first, cross_product_3d(axis, first)};
  }


  template <int dim>
  Drawing<dim>
  revolve(const std::vector<std::pair<double, double>> &profile,
          const Point<dim>                             &origin,
          const Tensor<1, dim>                         &axis)
  {
    Drawing<dim> result;
    if constexpr (dim == 3)
      {
        // Poles once, every other profile point on a ring.
        const auto [a, b]        = tangent_frame(axis);
        const unsigned int rings = profile.size() - 2;
        result.vertices.push_back(origin + profile.front().first * axis);
        for (unsigned int k = 1; k + 1 < profile.size(); ++k)
          for (unsigned int j = 0; j < segments; ++j)
            {
              const double phi = 2 * M_PI * j / segments;
              result.vertices.push_back(
                origin + profile[k].first * axis
                + profile[k].second * (std::cos(phi) * a + std::sin(phi) * b));
            }
        result.vertices.push_back(origin + profile.back().first * axis);
        const unsigned int last = result.vertices.size() - 1;
        const auto         ring = [](unsigned int k, unsigned int j) {
          return 1 + k * segments + j % segments;
        };
        for (unsigned int j = 0; j < segments; ++j)
          {
            result.triangles.insert(result.triangles.end(),
                                    {0, ring(0, j + 1), ring(0, j)});
            for (unsigned int k = 0; k + 1 < rings; ++k)
              result.triangles.insert(result.triangles.end(),
                                      {ring(k, j),
                                       ring(k, j + 1),
                                       ring(k + 1, j + 1),
                                       ring(k, j),
                                       ring(k + 1, j + 1),
                                       ring(k + 1, j)});
            result.triangles.insert(result.triangles.end(),
                                    {last,
                                     ring(rings - 1, j),
                                     ring(rings - 1, j + 1)});
          }
        orient_outwards(result);
      }
    else if constexpr (dim == 2)
      {
        // The polygon down one side and back up the other, as a fan about
        // the centre of the axis' span (inside a convex profile).
        const Tensor<1, 2> normal({-axis[1], axis[0]});
        const double       middle
          = 0.5 * (profile.front().first + profile.back().first);
        result.vertices.push_back(origin + middle * axis);
        for (const auto &[s, r] : profile)
          result.vertices.push_back(origin + s * axis + r * normal);
        for (unsigned int k = profile.size() - 1; k-- > 1;)
          result.vertices.push_back(origin + profile[k].first * axis
                                    - profile[k].second * normal);
        const unsigned int n = result.vertices.size() - 1;
        for (unsigned int k = 0; k < n; ++k)
          result.triangles.insert(result.triangles.end(),
                                  {0, 1 + k, 1 + (k + 1) % n});
        orient_outwards(result);
      }
    else
      {
        (void)profile, (void)origin, (void)axis;
      }
    return result;
  }


  std::vector<std::pair<double, double>>
  capsule_profile(const double length, const double radius)
  {
    // A half circle about 0 from the pole at -radius to the equator, the
    // shaft, a half circle about length to the pole at length + radius.
    std::vector<std::pair<double, double>> profile;
    const unsigned int                     quarter = segments / 4;
    for (unsigned int k = 0; k <= quarter; ++k)
      {
        const double angle = M_PI - 0.5 * M_PI * k / quarter;
        profile.emplace_back(radius * std::cos(angle),
                             radius * std::sin(angle));
      }
    for (unsigned int k = length > 0 ? 0 : 1; k <= quarter; ++k)
      {
        const double angle = 0.5 * M_PI - 0.5 * M_PI * k / quarter;
        profile.emplace_back(length + radius * std::cos(angle),
                             radius * std::sin(angle));
      }
    profile.front().second = profile.back().second = 0;
    return profile;
  }


  template <int dim>
  double
  enclosed_measure(const Drawing<dim> &d)
  {
    double sum = 0;
    for (unsigned int t = 0; t + 2 < d.triangles.size(); t += 3)
      {
        const Point<dim> &a = d.vertices[d.triangles[t]];
        const Point<dim> &b = d.vertices[d.triangles[t + 1]];
        const Point<dim> &c = d.vertices[d.triangles[t + 2]];
        if constexpr (dim == 3)
          sum += a * cross_product_3d(b - a, c - a) / 6;
        else if constexpr (dim == 2)
          sum += ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
                 / 2;
      }
    return sum;
  }


  template <int dim>
  void
  orient_outwards(Drawing<dim> &d)
  {
    if (enclosed_measure(d) < 0)
      for (unsigned int t = 0; t + 2 < d.triangles.size(); t += 3)
        std::swap(d.triangles[t + 1], d.triangles[t + 2]);
  }


  template Drawing<1>
  revolve(const std::vector<std::pair<double, double>> &,
          const Point<1> &,
          const Tensor<1, 1> &);
  template Drawing<2>
  revolve(const std::vector<std::pair<double, double>> &,
          const Point<2> &,
          const Tensor<1, 2> &);
  template Drawing<3>
  revolve(const std::vector<std::pair<double, double>> &,
          const Point<3> &,
          const Tensor<1, 3> &);
  template double
  enclosed_measure(const Drawing<1> &);
  template double
  enclosed_measure(const Drawing<2> &);
  template double
  enclosed_measure(const Drawing<3> &);
  template void
  orient_outwards(Drawing<1> &);
  template void
  orient_outwards(Drawing<2> &);
  template void
  orient_outwards(Drawing<3> &);
} // namespace tissuefem::contact::drawing
