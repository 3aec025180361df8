#include <tissuefem/solid/three_field_dilatation.h>

namespace tissuefem::solid
{
  void
  ThreeFieldDilatation::begin(const unsigned int n_cells)
  {
    cells.assign(n_cells, Cell());
    is_active  = true;
    initialize = true;
  }


  void
  ThreeFieldDilatation::set_linearization(const unsigned int    c,
                                          std::vector<double> &&b,
                                          std::vector<double> &&C,
                                          const double          Theta,
                                          const double          volume)
  {
    Cell &cell  = cells[c];
    cell.b      = std::move(b);
    cell.C      = std::move(C);
    cell.Theta  = Theta;
    cell.volume = volume;
  }


  void
  ThreeFieldDilatation::add_condensed_rows(const unsigned int c,
                                           const double       r,
                                           const double       R_theta,
                                           Vector<double>    &rhs)
  {
    Cell &cell        = cells[c];
    cell.r            = r;
    cell.R_theta      = R_theta;
    const double rest = R_theta + cell.Theta * r;
    for (unsigned int i = 0; i < rhs.size(); ++i)
      rhs[i] += cell.C[i] * r + cell.b[i] * rest;
  }


  void
  ThreeFieldDilatation::predict(const unsigned int         c,
                                const std::vector<double> &du)
  {
    Cell  &cell = cells[c];
    double b_du = 0, C_du = 0;
    for (unsigned int i = 0; i < du.size(); ++i)
      {
        b_du += cell.b[i] * du[i];
        C_du += cell.C[i] * du[i];
      }
    cell.base_theta = cell.theta;
    cell.base_p     = cell.p;
    cell.d_theta    = b_du + cell.r;
    cell.d_p = (cell.R_theta + C_du + cell.Theta * cell.d_theta) / cell.volume;
  }


  void
  ThreeFieldDilatation::trial(const double alpha)
  {
    for (Cell &cell : cells)
      {
        cell.theta = cell.base_theta + alpha * cell.d_theta;
        cell.p     = cell.base_p + alpha * cell.d_p;
      }
  }
} // namespace tissuefem::solid
