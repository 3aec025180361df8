// The Solid's side of a formulation's own unknowns (IterationUnknowns; the
// three-field mean dilatation element's, ThreeFieldDilatation): an implicit
// step drives them through the solid, which forwards to the formulation.
#include <tissuefem/solid/solid.h>

namespace tissuefem::solid
{
  template <int dim>
  IterationUnknowns *
  Solid<dim>::iteration_unknowns()
  {
    return element->iteration_unknowns() ? this : nullptr;
  }


  template <int dim>
  void
  Solid<dim>::begin_iterations(const double start_time)
  {
    element->iteration_unknowns()->begin_iterations(start_time);
  }


  template <int dim>
  void
  Solid<dim>::predict_update(const VectorType &du)
  {
    // The formulation reads the increment cell by cell: ghosted, with its
    // hanging values set.
    VectorType ghosted_du;
    discretization.initialize_vector(ghosted_du, true);
    make_ghosted(du, ghosted_du);
    element->iteration_unknowns()->predict_update(ghosted_du);
  }


  template <int dim>
  void
  Solid<dim>::set_step_length(const double alpha)
  {
    element->iteration_unknowns()->set_step_length(alpha);
  }


  template <int dim>
  void
  Solid<dim>::end_iterations(const bool converged)
  {
    element->iteration_unknowns()->end_iterations(converged);
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
