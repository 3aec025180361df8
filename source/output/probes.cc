#include <tissuefem/base/input_error.h>
#include <tissuefem/geometry/point_locator.h>
#include <tissuefem/output/probes.h>

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
    // The cell of the process that owns it, whichever cells a process
    // holds.
    const geometry::PointLocator<dim> locator(mapping,
                                              dof_handler.get_triangulation(),
                                              /*owned_only=*/true);
    for (const auto &p : points)
      {
        const auto found
          = locator.locate_among_processes(p, parallel_tools::communicator());
        if (!found.anywhere)
          {
            std::ostringstream where;
            where << "(" << p << ")";
            throw InputError("Parameter '" + parameter + "': point "
                             + where.str() + " lies outside the mesh");
          }
        if (found.here)
          {
            cells.emplace_back(&dof_handler.get_triangulation(),
                               found.here->cell->level(),
                               found.here->cell->index(),
                               &dof_handler);
            reference_points.push_back(found.here->reference);
          }
        else
          {
            cells.emplace_back();
            reference_points.emplace_back();
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
      if (cells[p].state() == IteratorState::valid)
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
