// The solid's prescribed displacements: the Dirichlet values at a time
// (from support points found once per mesh), writing them into states,
// the initial state, and holding vertices for a grasping tool (see
// solid.cc for assembly).
#include <deal.II/base/function.h>
#include <deal.II/numerics/vector_tools.h>

#include <tissuefem/solid/solid.h>

namespace tissuefem::solid
{
  template <int dim>
  void
  Solid<dim>::find_dirichlet_points()
  {
    // deal.II's interpolation itself tells where it evaluates: interpolating
    // the coordinate functions x_k and the component index gives each
    // constrained dof's support point and component, exactly as
    // interpolate_boundary_values() would use them.
    class Coordinate : public Function<dim>
    {
    public:
      Coordinate(const unsigned int k)
          : Function<dim>(dim)
          , k(k)
      {
      }
      double
      value(const Point<dim> &p, const unsigned int component) const override
      {
        return k < dim ? p[k] : component;
      }

    private:
      const unsigned int k;
    };
    dirichlet_points.clear();
    for (const auto &d : boundary_conditions.dirichlet)
      {
        std::vector<std::map<types::global_dof_index, double>> found(dim + 1);
        for (unsigned int k = 0; k <= dim; ++k)
          VectorTools::interpolate_boundary_values(*discretization.mapping,
                                                   discretization.dof_handler,
                                                   d.id,
                                                   Coordinate(k),
                                                   found[k],
                                                   d.mask);
        std::vector<DirichletPoint> points;
        const auto                 &owned = discretization.locally_owned;
        d.displacement->set_time(0);
        for (const auto &[dof, component] : found[dim])
          {
            DirichletPoint entry{dof,
                                 Point<dim>(),
                                 static_cast<unsigned int>(component)};
            for (unsigned int k = 0; k < dim; ++k)
              entry.point[k] = found[k].at(dof);
            if (owned.is_element(dof)
                && !discretization.hanging_node_constraints.is_constrained(dof))
              entry.local = owned.index_within_set(dof);
            if (!d.time_dependent)
              entry.value = d.displacement->value(entry.point, entry.component);
            points.push_back(entry);
          }
        dirichlet_points.push_back(std::move(points));
      }
  }


  template <int dim>
  template <typename Visitor>
  void
  Solid<dim>::visit_dirichlet_values(const double   time,
                                     const Visitor &visit) const
  {
    // Later conditions win over earlier ones, held vertices over all: the
    // visitor sees the dofs in that order. Conditions without t keep the
    // values found per mesh (explicit steps ask every step).
    for (unsigned int c = 0; c < boundary_conditions.dirichlet.size(); ++c)
      {
        const auto &condition = boundary_conditions.dirichlet[c];
        condition.displacement->set_time(time);
        for (const auto &entry : dirichlet_points[c])
          visit(entry.dof,
                entry.local,
                condition.time_dependent
                  ? condition.displacement->value(entry.point, entry.component)
                  : entry.value);
      }
    if (held)
      {
        const auto  motion = held->motion(time);
        const auto &owned  = discretization.locally_owned;
        for (const auto &[dof, vertex, component] : held_dofs)
          visit(dof,
                owned.is_element(dof)
                    && !discretization.hanging_node_constraints.is_constrained(
                      dof)
                  ? static_cast<int>(owned.index_within_set(dof))
                  : -1,
                held_start.at(dof) + motion[component]);
      }
  }


  template <int dim>
  std::map<types::global_dof_index, double>
  Solid<dim>::dirichlet_values(const double time) const
  {
    std::map<types::global_dof_index, double> values;
    visit_dirichlet_values(time,
                           [&](const types::global_dof_index dof,
                               const int,
                               const double value) { values[dof] = value; });
    return values;
  }


  template <int dim>
  void
  Solid<dim>::apply_dirichlet_values(const double time, VectorType &u) const
  {
    // Owned entries are written in place (not through Trilinos' index
    // lookups and a compress).
    double *local = u.trilinos_vector()[0];
    visit_dirichlet_values(time,
                           [&](const types::global_dof_index,
                               const int    index,
                               const double value) {
                             if (index >= 0)
                               local[index] = value;
                           });
    if (discretization.has_hanging_nodes)
      discretization.hanging_node_constraints.distribute(u);
  }


  template <int dim>
  void
  Solid<dim>::zero_constrained_entries(VectorType &v) const
  {
    discretization.constraints.set_zero(v);
  }


  template <int dim>
  void
  Solid<dim>::initial_state(VectorType &u, VectorType &v) const
  {
    initialize_vector(u);
    initialize_vector(v);
    boundary_conditions.initial_displacement->set_time(0);
    boundary_conditions.initial_velocity->set_time(0);
    VectorTools::interpolate(*discretization.mapping,
                             discretization.dof_handler,
                             *boundary_conditions.initial_displacement,
                             u);
    VectorTools::interpolate(*discretization.mapping,
                             discretization.dof_handler,
                             *boundary_conditions.initial_velocity,
                             v);
    discretization.hanging_node_constraints.distribute(u);
    discretization.hanging_node_constraints.distribute(v);
  }


  template <int dim>
  void
  Solid<dim>::hold(const std::vector<unsigned int>                   &vertices,
                   const std::function<Tensor<1, dim>(const double)> &motion,
                   const VectorType                                  &u)
  {
    VectorType ghosted;
    discretization.initialize_vector(ghosted, true);
    make_ghosted(u, ghosted);
    // Where the held vertices start, before setup() announces the new
    // constraints (those told may apply them at once). Holding changes
    // constraints, not the numbering.
    held_start.clear();
    for (const auto &[dof, vertex, component] :
         held_vertex_dofs(discretization.dof_handler,
                          vertices,
                          discretization.locally_relevant))
      held_start[dof] = ghosted[dof];
    held = Held{vertices, motion};
    setup();
  }


  template <int dim>
  void
  Solid<dim>::release()
  {
    held.reset();
    setup();
  }

#define TISSUEFEM_INSTANTIATE(dim)                                             \
  template void Solid<dim>::find_dirichlet_points();                           \
  template std::map<types::global_dof_index, double>                           \
                Solid<dim>::dirichlet_values(const double) const;              \
  template void Solid<dim>::apply_dirichlet_values(const double, VectorType &) \
    const;                                                                     \
  template void Solid<dim>::zero_constrained_entries(VectorType &) const;      \
  template void Solid<dim>::initial_state(VectorType &, VectorType &) const;   \
  template void Solid<dim>::hold(                                              \
    const std::vector<unsigned int> &,                                         \
    const std::function<Tensor<1, dim>(const double)> &,                       \
    const VectorType &);                                                       \
  template void Solid<dim>::release();
  TISSUEFEM_INSTANTIATE(1)
  TISSUEFEM_INSTANTIATE(2)
  TISSUEFEM_INSTANTIATE(3)
#undef TISSUEFEM_INSTANTIATE
} // namespace tissuefem::solid
