// The window of self-contact pressures (contact/self_contact.h) over which
// crushed tetrahedral blocks of the invertible neo-Hookean model recover
// their rest shape: the starts of tests/unit/crushed_starts.h (collapsed
// to a plane, a line, a point; nodes within 1 % of them; random and smooth
// scrambles) with SEEDS seeds each for the randomized ones, at pressures
// from a quarter of the shear modulus to five times it, each start run to
// t = 3 by backward Euler (dt = 0.02) as the unit test does. Prints, per
// pressure, how many starts recovered (distance from the rest shape below
// 1e-3 of the block's length), stayed tangled, or failed (Newton gave up
// at the smallest step), and each start's outcome in order (r, t, f; the
// first 18 are tests/unit/crushed_starts.h's for seeds 1 to 3, in another
// order: the three collapses, then per seed the three near-collapses and
// the two scrambles).
//
//   self_contact_window [SEEDS] [CELLS] [TANGENT] [RATIOS]
//
// defaults 6, simplex, false (the 'Self contact tangent'), and the
// pressures over the shear modulus 0,0.25,0.5,0.8,1,1.3,2,3,5.
//
// Build: make self_contact_window (not part of 'make all').

#include "../tests/unit/crushed_starts.h"

#include <tissuefem/base/parameter_tools.h>

#include <cstdlib>

using namespace tissuefem_tests;

namespace
{
  /// The starts of crushed_starts() with @p seeds seeds for the random ones.
  std::vector<std::pair<std::string, std::string>>
  starts(const unsigned int seeds)
  {
    const std::string collapse[3][3] = {{"0", "0", "0.5 - z"},
                                        {"0.5 - x", "0.5 - y", "0"},
                                        {"0.5 - x", "0.5 - y", "0.5 - z"}};
    const std::string shapes[3]      = {"plane", "line", "point"};
    const auto        join           = [](const std::string(&c)[3]) {
      return c[0] + "; " + c[1] + "; " + c[2];
    };
    std::vector<std::pair<std::string, std::string>> result;
    for (unsigned int k = 0; k < 3; ++k)
      result.emplace_back("collapsed to a " + shapes[k], join(collapse[k]));
    for (unsigned int seed = 1; seed <= seeds; ++seed)
      {
        for (unsigned int k = 0; k < 3; ++k)
          {
            std::string d[3];
            for (unsigned int c = 0; c < 3; ++c)
              d[c]
                = (collapse[k][c] == "0" ? ""
                                         : "0.99*(" + collapse[k][c] + ") + ")
                  + "0.003*" + random_field(seed, c);
            result.emplace_back("nearly a " + shapes[k], join(d));
          }
        std::string r[3], s[3];
        for (unsigned int c = 0; c < 3; ++c)
          {
            r[c] = "0.5*" + random_field(seed, c);
            s[c] = "0.5*" + smooth_field(seed, c);
          }
        result.emplace_back("random scramble", join(r));
        result.emplace_back("smooth scramble", join(s));
      }
    return result;
  }
} // namespace


int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const unsigned int  seeds   = argc > 1 ? std::atoi(argv[1]) : 6;
  const std::string   cells   = argc > 2 ? argv[2] : "simplex";
  const std::string   tangent = argc > 3 ? argv[3] : "true";
  std::vector<double> ratios  = {0., 0.25, 0.5, 0.8, 1., 1.3, 2., 3., 5.};
  if (argc > 4)
    ratios = tissuefem::parse_numbers(argv[4], "ratios");
  // E = 1000 Pa, nu = 0.3 (crushed_starts.h): shear modulus 384.6 Pa.
  const double shear = 1000 / (2 * 1.3);
  const auto   all   = starts(seeds);
  std::cout << cells << ", tangent " << tangent << ", " << all.size()
            << " starts; pressure over the shear modulus: recovered / "
               "tangled / failed\n";
  for (const double ratio : ratios)
    {
      unsigned int recovered = 0, tangled = 0, failed = 0;
      // Per start in order: r(ecovered), t(angled), f(ailed).
      std::string outcomes;
      for (const auto &[name, start] : all)
        {
          std::ostringstream muted;
          auto              *screen   = std::cout.rdbuf(muted.rdbuf());
          double             distance = -1;
          try
            {
              distance
                = recover(cells, start, std::to_string(ratio * shear), tangent);
            }
          catch (const std::exception &)
            {
            }
          std::cout.rdbuf(screen);
          const char outcome = distance < 0 ? 'f' : distance < 1e-3 ? 'r' : 't';
          outcomes += outcome;
          recovered += outcome == 'r';
          tangled += outcome == 't';
          failed += outcome == 'f';
        }
      std::cout << "  p_c = " << ratio << " mu (" << ratio * shear
                << " Pa): " << recovered << " / " << tangled << " / " << failed
                << "  " << outcomes << std::endl;
    }
  return 0;
}
