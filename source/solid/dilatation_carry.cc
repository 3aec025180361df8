#include <deal.II/fe/fe_values.h>

#include <tissuefem/solid/dilatation_carry.h>

#include <algorithm>
#include <cmath>

namespace tissuefem::solid
{
  template <int dim>
  std::vector<std::pair<double, double>>
  DilatationCarry<dim>::cell_dilatations(const DoFHandler<dim> &dof_handler,
                                         const Mapping<dim>    &mapping,
                                         const Quadrature<dim> &quadrature,
                                         const Vector<double>  &u)
  {
    std::vector<std::pair<double, double>> result(
      dof_handler.get_triangulation().n_active_cells(), {0., 0.});
    FEValues<dim>                    fe_values(mapping,
                            dof_handler.get_fe(),
                            quadrature,
                            update_gradients | update_JxW_values);
    std::vector<Tensor<2, dim>>      gradients(quadrature.size());
    const FEValuesExtractors::Vector displacement(0);
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (cell->is_artificial())
          continue;
        fe_values.reinit(cell);
        fe_values[displacement].get_function_gradients(u, gradients);
        double integral = 0, volume = 0;
        for (unsigned int q = 0; q < quadrature.size(); ++q)
          {
            integral += determinant(unit_symmetric_tensor<dim>() + gradients[q])
                        * fe_values.JxW(q);
            volume += fe_values.JxW(q);
          }
        result[cell->active_cell_index()] = {integral / volume, volume};
      }
    return result;
  }


  template <int dim>
  void
  DilatationCarry<dim>::record(const DoFHandler<dim> &dof_handler,
                               const Mapping<dim>    &mapping,
                               const Quadrature<dim> &quadrature,
                               const Vector<double>  &u,
                               const double           time)
  {
    carried.clear();
    merged.clear();
    const auto theta = cell_dilatations(dof_handler, mapping, quadrature, u);
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (cell->is_artificial())
          continue;
        const unsigned int i = cell->active_cell_index();
        // What the cell carries now, so that a release under way goes on
        // from where it is.
        const double handed_on = theta[i].first * factor(i, time);
        if (cell->coarsen_flag_set())
          {
            auto &sums = merged[cell->parent()->id()];
            sums.first += theta[i].second * handed_on;
            sums.second += theta[i].second;
          }
        else
          carried[cell->id()] = handed_on;
      }
  }


  template <int dim>
  void
  DilatationCarry<dim>::finish(const DoFHandler<dim> &dof_handler,
                               const Mapping<dim>    &mapping,
                               const Quadrature<dim> &quadrature,
                               const Vector<double>  &u,
                               const double           time,
                               const double           duration)
  {
    Assert(duration > 0, ExcMessage("a release needs a positive duration"));
    log_ratio.assign(dof_handler.get_triangulation().n_active_cells(), 0.);
    start            = time;
    this->duration   = duration;
    const auto theta = cell_dilatations(dof_handler, mapping, quadrature, u);
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (cell->is_artificial())
          continue;
        double target = 0;
        if (const auto own = carried.find(cell->id()); own != carried.end())
          target = own->second;
        else if (const auto sums = merged.find(cell->id());
                 sums != merged.end())
          target = sums->second.first / sums->second.second;
        else if (cell->level() > 0)
          if (const auto parent = carried.find(cell->parent()->id());
              parent != carried.end())
            target = parent->second;
        const double own_theta = theta[cell->active_cell_index()].first;
        // Nothing carried into a cell inverted on either mesh: its Fbar is
        // not defined anyway, and assembly reports it.
        if (target > 0 && own_theta > 0)
          log_ratio[cell->active_cell_index()] = std::log(target / own_theta);
      }
    carried.clear();
    merged.clear();
  }


  template <int dim>
  double
  DilatationCarry<dim>::factor(const unsigned int cell_index,
                               const double       time) const
  {
    if (cell_index >= log_ratio.size())
      return 1;
    const double w = std::clamp(1 - (time - start) / duration, 0., 1.);
    return w > 0 ? std::exp(w * log_ratio[cell_index]) : 1.;
  }


  template <int dim>
  void
  DilatationCarry<dim>::clear()
  {
    carried.clear();
    merged.clear();
    log_ratio.clear();
  }


  template class DilatationCarry<1>;
  template class DilatationCarry<2>;
  template class DilatationCarry<3>;
} // namespace tissuefem::solid
