// Contact's broad-phase tree (contact/face_tree.h) against the brute force
// it replaces: for random balls (fixed seeds) and 1-Lipschitz distances
// (spheres, the outside of a sphere, half-spaces), near() returns exactly
// the balls i with g(c_i) - r_i - margin <= per_size * size_i, computed one
// by one; with and without a margin and a threshold, after the balls have
// moved and the tree been refitted (its hierarchy then no longer matches
// the balls), and with one ball broken (a NaN centre: every query must
// return it). A tree that pruned with a box not holding its balls, or
// forgot the margin or the threshold, returns fewer balls than the brute
// force and fails here. Also: a small obstacle costs far fewer distance
// evaluations than there are balls (the point of the tree).

#include <deal.II/base/point.h>

#include <tissuefem/contact/face_tree.h>

#include "../tests.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <string>
#include <vector>

using namespace dealii;
using namespace tissuefem;

namespace
{
  template <int dim>
  Point<dim>
  random_point(tissuefem_tests::Random &random, const double scale)
  {
    Point<dim> p;
    for (unsigned int d = 0; d < dim; ++d)
      p[d] = scale * random.uniform();
    return p;
  }


  template <int dim>
  std::vector<std::pair<std::string, std::function<double(const Point<dim> &)>>>
  distances(tissuefem_tests::Random &random)
  {
    std::vector<
      std::pair<std::string, std::function<double(const Point<dim> &)>>>
      list;
    for (unsigned int k = 0; k < 3; ++k)
      {
        const Point<dim> c = random_point<dim>(random, 1.);
        const double     r = 0.05 + 0.2 * (random.uniform() + 1);
        list.emplace_back("sphere", [c, r](const Point<dim> &y) {
          return y.distance(c) - r;
        });
        list.emplace_back("outside of a sphere", [c, r](const Point<dim> &y) {
          return r + 0.5 - y.distance(c);
        });
        Tensor<1, dim> n;
        for (unsigned int d = 0; d < dim; ++d)
          n[d] = random.uniform();
        n /= n.norm();
        const double h = 0.5 * random.uniform();
        list.emplace_back("half-space",
                          [n, h](const Point<dim> &y) { return n * y - h; });
      }
    return list;
  }


  template <int dim>
  void
  check(const std::string &label, const std::uint64_t seed)
  {
    tissuefem_tests::Random random(seed);
    const unsigned int      n = 3000;
    std::vector<Point<dim>> centres(n);
    std::vector<double>     radii(n), sizes(n);
    for (unsigned int i = 0; i < n; ++i)
      {
        centres[i] = random_point<dim>(random, 1.);
        radii[i]   = 0.01 * (random.uniform() + 1);
        sizes[i]   = 0.02 + 0.02 * (random.uniform() + 1);
      }
    contact::FaceTree<dim> tree;
    tree.build(centres, radii, sizes);
    const auto   obstacles  = distances<dim>(random);
    unsigned int mismatches = 0, queries = 0, answers = 0;
    unsigned int fewest_evals = n;
    const auto   compare = [&](const double margin, const double per_size) {
      for (const auto &[name, g] : obstacles)
        {
          std::vector<unsigned int> found;
          const unsigned int        evaluations
            = tree.near(g, margin, per_size, found);
          std::sort(found.begin(), found.end());
          std::vector<unsigned int> expected;
          for (unsigned int i = 0; i < n; ++i)
            if (!(g(centres[i]) - radii[i] - margin > per_size * sizes[i]))
              expected.push_back(i);
          mismatches += found == expected ? 0 : 1;
          answers += expected.size();
          ++queries;
          if (name == "sphere")
            fewest_evals = std::min(fewest_evals, evaluations);
        }
    };
    // Every margin and threshold, against the brute force.
    const auto agree = [&](const std::string &what) {
      mismatches = queries = answers = 0;
      for (const double margin : {0., 0.03})
        for (const double per_size : {0., 2.})
          compare(margin, per_size);
      tissuefem_tests::check(mismatches == 0 && answers > 0,
                             label + what,
                             std::to_string(mismatches) + " of "
                               + std::to_string(queries) + " queries differ");
    };
    agree(": the balls near() returns are those of the brute force");
    tissuefem_tests::check(fewest_evals < n / 5,
                           label
                             + ": a sphere costs fewer distance "
                               "evaluations than a fifth of the balls",
                           std::to_string(fewest_evals) + " of "
                             + std::to_string(n));

    // Moved by up to 0.2 each, radii changed, sizes kept: refitted.
    for (unsigned int i = 0; i < n; ++i)
      {
        centres[i] += random_point<dim>(random, 0.2);
        radii[i] = 0.03 * (random.uniform() + 1);
      }
    tree.refit(centres, radii);
    agree(": after the balls moved and the tree was refitted, the same as "
          "the brute force");

    // A broken ball is found by every query, wherever it would lie.
    const unsigned int broken = n / 3;
    centres[broken][0]        = std::numeric_limits<double>::quiet_NaN();
    tree.refit(centres, radii);
    bool always = true;
    for (const auto &[name, g] : obstacles)
      {
        std::vector<unsigned int> found;
        tree.near(g, 0., 0., found);
        always
          = always
            && std::find(found.begin(), found.end(), broken) != found.end();
      }
    tissuefem_tests::check(always,
                           label
                             + ": a ball with a NaN centre is returned "
                               "by every query",
                           "missed");
  }
} // namespace


int
main()
{
  check<2>("2D", 20261128);
  check<3>("3D", 20261129);
  return tissuefem_tests::exit_status();
}
