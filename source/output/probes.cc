#include <tissuefem/base/input_error.h>
#include <tissuefem/geometry/point_locator.h>
#include <tissuefem/output/probes.h>

#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>

#include <limits>
#include <sstream>

namespace tissuefem::output
{
  template <int dim>
  Probes<dim>::Probes(const std::vector<Point<dim>> &points,
                      const Mapping<dim>            &mapping,
                      const DoFHandler<dim>         &dof_handler,
                      const std::string             &parameter)
      : locations(points)
      , dof_handler(dof_handler)
  {
    // Each process looks among its own cells, then all take the best
    // candidate of any process by the locator's own rule (deepest inside,
    // then lowest CellId): the same cell whichever cells a process holds.
    const geometry::PointLocator<dim> locator(mapping,
                                              dof_handler.get_triangulation(),
                                              /*owned_only=*/true);
    const double none = std::numeric_limits<double>::infinity();
    for (const auto &p : points)
      {
        const auto                           found = locator.locate(p);
        const std::pair<double, std::string> mine(
          found ? found->outside : none,
          found ? found->cell->id().to_string() : std::string());
        std::pair<double, std::string> best(none, std::string());
        for (const auto &[outside, id] :
             Utilities::MPI::all_gather(parallel_tools::communicator(), mine))
          if (outside < best.first
              || (outside == best.first && outside < none
                  && CellId(id) < CellId(best.second)))
            best = {outside, id};
        if (best.first == none)
          {
            std::ostringstream where;
            where << "(" << p << ")";
            throw InputError("Parameter '" + parameter + "': point "
                             + where.str() + " lies outside the mesh");
          }
        if (found && mine.second == best.second)
          {
            cells.emplace_back(&dof_handler.get_triangulation(),
                               found->cell->level(),
                               found->cell->index(),
                               &dof_handler);
            reference_points.push_back(found->reference);
            evaluates.push_back(true);
          }
        else
          {
            cells.emplace_back();
            reference_points.emplace_back();
            evaluates.push_back(false);
          }
      }
  }


  template <int dim>
  std::vector<Vector<double>>
  Probes<dim>::evaluate(const VectorType &u) const
  {
    const auto                          &fe = dof_handler.get_fe();
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    std::vector<double> flat(cells.size() * fe.n_components(), 0.);
    for (unsigned int p = 0; p < cells.size(); ++p)
      if (evaluates[p])
        {
          cells[p]->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            flat[p * fe.n_components() + fe.system_to_component_index(i).first]
              += u[dofs[i]] * fe.shape_value(i, reference_points[p]);
        }
    Utilities::MPI::sum(flat, parallel_tools::communicator(), flat);
    std::vector<Vector<double>> values(cells.size(),
                                       Vector<double>(fe.n_components()));
    for (unsigned int p = 0; p < cells.size(); ++p)
      for (unsigned int c = 0; c < fe.n_components(); ++c)
        values[p][c] = flat[p * fe.n_components() + c];
    return values;
  }

  template class Probes<1>;
  template class Probes<2>;
  template class Probes<3>;
} // namespace tissuefem::output
