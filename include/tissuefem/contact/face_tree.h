#pragma once

#include <deal.II/base/point.h>

#include <vector>

namespace tissuefem::contact
{
  using namespace dealii;

  /**
   * A bounding-volume tree over balls (the boundary faces of the tissue,
   * each a centre, a radius and a size), for the broad phase of contact:
   * which faces can lie within a threshold of an obstacle, found in
   * O(log n + answers) distance evaluations instead of one per face.
   *
   * The tree is built once for a set of balls (a median split along the
   * longest axis of the centres' box; its shape depends on the balls of
   * the build only) and refitted when they move: the boxes are recomputed
   * bottom up, the hierarchy kept. A refit tree answers exactly, only less
   * quickly the further the balls have moved from where they were built.
   *
   * Queries use only that an obstacle's distance g is 1-Lipschitz (a true
   * signed distance: doc/user_guide.md, "Obstacles and contact"): every
   * point within r of c has g >= g(c) - r. A node is a ball around its
   * box, so a subtree whose node's lower bound exceeds its threshold holds
   * no answer.
   */
  template <int dim>
  class FaceTree
  {
  public:
    /// Builds the tree over balls (@p centres, @p radii; length units)
    /// with a size each (@p sizes, length units, scaling the threshold of
    /// near()). All three of the same length.
    void
    build(const std::vector<Point<dim>> &centres,
          const std::vector<double>     &radii,
          const std::vector<double>     &sizes);

    /// The same balls (same number, same order, same sizes) moved.
    void
    refit(const std::vector<Point<dim>> &centres,
          const std::vector<double>     &radii);

    /// The number of balls of the last build.
    unsigned int
    size() const
    {
      return centre.size();
    }

    /// Ball @p i's centre and radius at the last build or refit.
    const Point<dim> &
    centre_of(const unsigned int i) const
    {
      return centre[i];
    }

    double
    radius_of(const unsigned int i) const
    {
      return radius[i];
    }

    /**
     * Appends to @p answers the index of every ball i with
     * g(centre_i) - radius_i - @p margin <= @p per_size * size_i, with
     * @p distance g a 1-Lipschitz function, in no particular order. The
     * @p margin bounds how far any point of a ball may have moved since
     * the last refit (length units). Returns the number of evaluations of
     * @p distance.
     */
    template <typename Distance>
    unsigned int
    near(const Distance            &distance,
         const double               margin,
         const double               per_size,
         std::vector<unsigned int> &answers) const;

  private:
    struct Node
    {
      Point<dim> low, high;
      /// The largest size below this node.
      double largest_size;
      /// Leaves: items [first, last) of order; inner nodes: children
      /// first and last (an index of nodes each).
      unsigned int first, last;
      bool         leaf;
    };

    /// Builds the subtree over order[first, last); returns its node.
    unsigned int
    split(const unsigned int first, const unsigned int last);

    /// The box of the balls order[first, last).
    void
    fit(Node &node) const;

    std::vector<Point<dim>>   centre;
    std::vector<double>       radius, size_of;
    std::vector<unsigned int> order;
    /// Parents before their children: a reverse pass refits bottom up.
    std::vector<Node> nodes;
  };


  template <int dim>
  template <typename Distance>
  unsigned int
  FaceTree<dim>::near(const Distance            &distance,
                      const double               margin,
                      const double               per_size,
                      std::vector<unsigned int> &answers) const
  {
    if (nodes.empty())
      return 0;
    unsigned int              evaluations = 0;
    std::vector<unsigned int> stack{0};
    while (!stack.empty())
      {
        const Node &node = nodes[stack.back()];
        stack.pop_back();
        if (node.leaf)
          {
            for (unsigned int k = node.first; k < node.last; ++k)
              {
                const unsigned int i = order[k];
                ++evaluations;
                // Written so that a NaN distance keeps the ball.
                if (!(distance(centre[i]) - radius[i] - margin
                      > per_size * size_of[i]))
                  answers.push_back(i);
              }
            continue;
          }
        const Point<dim> middle = 0.5 * (node.low + node.high);
        const double     reach  = 0.5 * node.low.distance(node.high);
        ++evaluations;
        if (distance(middle) - reach - margin > per_size * node.largest_size)
          continue;
        stack.push_back(node.first);
        stack.push_back(node.last);
      }
    return evaluations;
  }
} // namespace tissuefem::contact
