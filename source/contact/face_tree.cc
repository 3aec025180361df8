#include <deal.II/base/exceptions.h>

#include <tissuefem/contact/face_tree.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace tissuefem::contact
{
  namespace
  {
    /// Balls per leaf: a few distances at a leaf cost less than the
    /// node tests that would separate them.
    constexpr unsigned int leaf_size = 4;
  } // namespace


  template <int dim>
  void
  FaceTree<dim>::build(const std::vector<Point<dim>> &centres,
                       const std::vector<double>     &radii,
                       const std::vector<double>     &sizes)
  {
    AssertDimension(centres.size(), radii.size());
    AssertDimension(centres.size(), sizes.size());
    centre  = centres;
    radius  = radii;
    size_of = sizes;
    order.resize(centre.size());
    std::iota(order.begin(), order.end(), 0u);
    nodes.clear();
    if (!centre.empty())
      split(0, centre.size());
  }


  template <int dim>
  unsigned int
  FaceTree<dim>::split(const unsigned int first, const unsigned int last)
  {
    const unsigned int here = nodes.size();
    nodes.push_back({Point<dim>(), Point<dim>(), 0., first, last, true});
    fit(nodes[here]);
    if (last - first <= leaf_size)
      return here;
    // The longest axis of the centres' box (the balls' box would let one
    // large face decide the axis for all).
    Point<dim> low = centre[order[first]], high = low;
    for (unsigned int k = first; k < last; ++k)
      for (unsigned int d = 0; d < dim; ++d)
        {
          low[d]  = std::min(low[d], centre[order[k]][d]);
          high[d] = std::max(high[d], centre[order[k]][d]);
        }
    unsigned int axis = 0;
    for (unsigned int d = 1; d < dim; ++d)
      if (high[d] - low[d] > high[axis] - low[axis])
        axis = d;
    const unsigned int middle = first + (last - first) / 2;
    std::nth_element(order.begin() + first,
                     order.begin() + middle,
                     order.begin() + last,
                     [&](const unsigned int a, const unsigned int b) {
                       // NaN last: an order, even for a broken state.
                       const double x = centre[a][axis], y = centre[b][axis];
                       return std::isnan(y) ? !std::isnan(x) : x < y;
                     });
    const unsigned int left  = split(first, middle);
    const unsigned int right = split(middle, last);
    nodes[here].leaf         = false;
    nodes[here].first        = left;
    nodes[here].last         = right;
    return here;
  }


  template <int dim>
  void
  FaceTree<dim>::fit(Node &node) const
  {
    // Leaves hold items first..last, inner nodes their children's boxes.
    // A leaf is fitted to its balls; split() fits an inner node to its
    // balls too, before it knows its children.
    const auto grow = [&](const Point<dim> &low, const Point<dim> &high) {
      for (unsigned int d = 0; d < dim; ++d)
        {
          node.low[d]  = std::min(node.low[d], low[d]);
          node.high[d] = std::max(node.high[d], high[d]);
        }
    };
    for (unsigned int d = 0; d < dim; ++d)
      {
        node.low[d]  = std::numeric_limits<double>::infinity();
        node.high[d] = -std::numeric_limits<double>::infinity();
      }
    node.largest_size = 0;
    if (node.leaf)
      for (unsigned int k = node.first; k < node.last; ++k)
        {
          const unsigned int i = order[k];
          Point<dim>         low, high;
          // A ball that is not finite (a broken state) covers all space,
          // so that every node holding it is searched.
          bool finite = std::isfinite(radius[i]);
          for (unsigned int d = 0; d < dim; ++d)
            finite = finite && std::isfinite(centre[i][d]);
          for (unsigned int d = 0; d < dim; ++d)
            {
              constexpr double all = std::numeric_limits<double>::infinity();
              low[d]               = finite ? centre[i][d] - radius[i] : -all;
              high[d]              = finite ? centre[i][d] + radius[i] : all;
            }
          grow(low, high);
          node.largest_size = std::max(node.largest_size, size_of[i]);
        }
    else
      for (const unsigned int child : {node.first, node.last})
        {
          grow(nodes[child].low, nodes[child].high);
          node.largest_size
            = std::max(node.largest_size, nodes[child].largest_size);
        }
  }


  template <int dim>
  void
  FaceTree<dim>::refit(const std::vector<Point<dim>> &centres,
                       const std::vector<double>     &radii)
  {
    AssertDimension(centres.size(), centre.size());
    AssertDimension(radii.size(), radius.size());
    centre = centres;
    radius = radii;
    for (auto node = nodes.rbegin(); node != nodes.rend(); ++node)
      fit(*node);
  }


  template class FaceTree<1>;
  template class FaceTree<2>;
  template class FaceTree<3>;
} // namespace tissuefem::contact
