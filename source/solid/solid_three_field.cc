// The Solid's side of the three-field mean dilatation element: the
// IterationUnknowns an implicit step drives (ThreeFieldDilatation).
#include <tissuefem/solid/solid.h>

namespace tissuefem::solid
{
  template <int dim>
  IterationUnknowns *
  Solid<dim>::iteration_unknowns()
  {
    // Only the mean dilatation element has cell unknowns (the nodal
    // dilatation of P1 simplices is another formulation).
    return materials.mean_dilatation_formulation() ? this : nullptr;
  }


  template <int dim>
  void
  Solid<dim>::begin_iterations(const double start_time)
  {
    three_field.begin(cache.cells().size());
    three_field_start = start_time;
  }


  template <int dim>
  void
  Solid<dim>::predict_update(const VectorType &du)
  {
    VectorType ghosted_du;
    discretization.initialize_vector(ghosted_du, true);
    make_ghosted(du, ghosted_du);
    std::vector<double> du_cell(cache.n_dofs);
    for (unsigned int c = 0; c < cache.cells().size(); ++c)
      {
        const types::global_dof_index *dofs = cache.dofs(c);
        for (unsigned int i = 0; i < cache.n_dofs; ++i)
          du_cell[i] = ghosted_du[dofs[i]];
        three_field.predict(c, du_cell);
      }
  }


  template <int dim>
  void
  Solid<dim>::set_step_length(const double alpha)
  {
    three_field.trial(alpha);
  }


  template <int dim>
  void
  Solid<dim>::end_iterations(const bool converged)
  {
    three_field.end();
    // A carried dilatation is the first iterate of the step after a mesh
    // change; once a step has converged on the new mesh it has served
    // (a retried step starts from it again).
    if (converged)
      carry.clear();
  }


  // The class is instantiated in solid.cc; these members here.
#define TISSUEFEM_INSTANTIATE(dim)                                            \
  template IterationUnknowns *Solid<dim>::iteration_unknowns();               \
  template void               Solid<dim>::begin_iterations(const double);     \
  template void               Solid<dim>::predict_update(const VectorType &); \
  template void               Solid<dim>::set_step_length(const double);      \
  template void               Solid<dim>::end_iterations(const bool);
  TISSUEFEM_INSTANTIATE(1)
  TISSUEFEM_INSTANTIATE(2)
  TISSUEFEM_INSTANTIATE(3)
#undef TISSUEFEM_INSTANTIATE
} // namespace tissuefem::solid
