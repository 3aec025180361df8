#include <deal.II/fe/fe_values.h>

#include <tissuefem/adaptation/indicator.h>
#include <tissuefem/adaptation/stress_jump.h>
#include <tissuefem/base/parallel.h>

#include <algorithm>
#include <map>

namespace tissuefem::adaptation
{
  namespace
  {
    /// Traction P N of the displacement gradients @p grad_u at normal @p N.
    template <int dim>
    Tensor<1, dim>
    traction(const materials::MaterialSet<dim> &materials,
             const types::material_id           id,
             const Point<dim>                  &X,
             const Tensor<2, dim>              &grad_u,
             const Tensor<1, dim>              &N)
    {
      const Tensor<1, dim> fibre = materials.any_uses_fibres()
                                     ? materials.fibre_direction(X)
                                     : Tensor<1, dim>();
      return materials.material(id).stress(unit_symmetric_tensor<dim>()
                                             + grad_u,
                                           fibre)
             * N;
    }


    /**
     * The terms of the stress-jump indicator for one state: what does not
     * depend on the cell (face values, prescribed components and tractions
     * per boundary id, the materials' scales) is set up once, then each
     * cell's sum over its faces is asked for in turn.
     */
    template <int dim>
    class StressJumpTerms
    {
    public:
      StressJumpTerms(const solid::Solid<dim> &solid,
                      const VectorType        &u,
                      const double             time)
          : d(solid.get_discretization())
          , materials(solid.get_materials())
          , u(u)
          , n_q(d.face_quadrature.size())
          , here(*d.mapping,
                 *d.fe,
                 d.face_quadrature,
                 update_gradients | update_normal_vectors
                   | update_quadrature_points | update_JxW_values)
          , grad_here(n_q)
          , grad_there(n_q)
          , t_value(dim)
      {
        const auto &bc = solid.get_boundary_conditions();
        for (const auto &c : bc.dirichlet)
          held[c.id] = c.mask;
        for (const auto &c : bc.neumann)
          {
            c.traction->set_time(time);
            tractions[c.id] = c.traction.get();
          }
        load_factor = bc.load_factor_in_force(time);
      }

      /// sum_F h_F int_F |r|^2 over the faces of @p cell, with r the
      /// traction residual on boundary faces and the traction jump on
      /// interior ones.
      double
      face_sum(const typename DoFHandler<dim>::active_cell_iterator &cell)
      {
        double sum = 0;
        for (const unsigned int f : cell->face_indices())
          {
            here.reinit(cell, f);
            here[displacement].get_function_gradients(u, grad_here);
            // h_K stands for h_F (shape-regular cells; faces are points in
            // 1D).
            const double h_F = cell->diameter();
            if (cell->face(f)->at_boundary())
              {
                sum += h_F * boundary_integral(cell, f);
                continue;
              }
            // A finer neighbour: its cells see this face from their side.
            if (cell->neighbor(f)->has_children())
              continue;
            const auto   neighbor = cell->neighbor(f);
            const double integral = jump_integral(cell, neighbor);
            // Same level: each side carries half; coarser neighbour: the
            // fine side carries it all.
            sum += (neighbor->level() == cell->level() ? 0.5 : 1.) * h_F
                   * integral;
          }
        return sum;
      }

      /// 2 mu = 2 A_0101 at F = I for material @p id: scales the traction
      /// residual to the units of the displacement gradient.
      double
      scale(const types::material_id id)
      {
        auto it = two_mu.find(id);
        if (it != two_mu.end())
          return it->second;
        Tensor<2, dim> P;
        Tensor<4, dim> A;
        materials.material(id).stress_and_tangent(unit_symmetric_tensor<dim>(),
                                                  Tensor<1, dim>(),
                                                  P,
                                                  A,
                                                  materials.tangent_method());
        // (In 1D, A_0000 = lambda + 2 mu stands for 2 mu.)
        const unsigned int j = dim > 1 ? 1 : 0;
        return two_mu[id] = (dim > 1 ? 2 : 1) * std::max(A[0][j][0][j], 1e-300);
      }

    private:
      const solid::Discretization<dim>    &d;
      const materials::MaterialSet<dim>   &materials;
      const VectorType                    &u;
      const unsigned int                   n_q;
      FEFaceValues<dim>                    here;
      const FEValuesExtractors::Vector     displacement{0};
      std::vector<Tensor<2, dim>>          grad_here, grad_there;
      std::map<types::material_id, double> two_mu;
      // Prescribed components and tractions per boundary id.
      std::map<types::boundary_id, ComponentMask>   held;
      std::map<types::boundary_id, Function<dim> *> tractions;
      Vector<double>                                t_value;
      /// 'Load factor' at the time: it scales the tractions.
      double load_factor = 1;

      /// int_F |P N - t|^2 over boundary face @p f (here), without the
      /// prescribed components.
      double
      boundary_integral(
        const typename DoFHandler<dim>::active_cell_iterator &cell,
        const unsigned int                                    f)
      {
        double     integral = 0;
        const auto id       = cell->face(f)->boundary_id();
        const auto mask = held.count(id) ? held[id] : ComponentMask(dim, false);
        for (unsigned int q = 0; q < n_q; ++q)
          {
            Tensor<1, dim> r = traction(materials,
                                        cell->material_id(),
                                        here.quadrature_point(q),
                                        grad_here[q],
                                        here.normal_vector(q));
            if (tractions.count(id))
              {
                tractions[id]->vector_value(here.quadrature_point(q), t_value);
                for (unsigned int c = 0; c < dim; ++c)
                  r[c] -= load_factor * t_value[c];
              }
            for (unsigned int c = 0; c < dim; ++c)
              if (mask.size() == dim && mask[c])
                r[c] = 0;
            integral += r.norm_square() * here.JxW(q);
          }
        return integral;
      }

      /// int_F |P N - P' N|^2 over the face (here) shared with @p neighbor,
      /// with the neighbour's gradients at the same points.
      double
      jump_integral(
        const typename DoFHandler<dim>::active_cell_iterator &cell,
        const typename DoFHandler<dim>::active_cell_iterator &neighbor)
      {
        std::vector<Point<dim>> unit(n_q);
        for (unsigned int q = 0; q < n_q; ++q)
          unit[q]
            = d.mapping->transform_real_to_unit_cell(neighbor,
                                                     here.quadrature_point(q));
        FEValues<dim> at_points(*d.mapping,
                                *d.fe,
                                Quadrature<dim>(unit),
                                update_gradients);
        at_points.reinit(neighbor);
        at_points[displacement].get_function_gradients(u, grad_there);
        double integral = 0;
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const Tensor<1, dim> &N    = here.normal_vector(q);
            const Tensor<1, dim>  jump = traction(materials,
                                                 cell->material_id(),
                                                 here.quadrature_point(q),
                                                 grad_here[q],
                                                 N)
                                        - traction(materials,
                                                   neighbor->material_id(),
                                                   here.quadrature_point(q),
                                                   grad_there[q],
                                                   N);
            integral += jump.norm_square() * here.JxW(q);
          }
        return integral;
      }
    };
  } // namespace


  template <int dim>
  void
  stress_jump_indicator(const solid::Solid<dim> &solid,
                        const VectorType        &u,
                        const double             time,
                        Vector<float>           &indicator)
  {
    const auto          &d = solid.get_discretization();
    StressJumpTerms<dim> terms(solid, u, time);
    indicator.reinit(d.dof_handler.get_triangulation().n_active_cells());
    for (const auto &cell : d.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const double sum = terms.face_sum(cell);
          const double s   = terms.scale(cell->material_id());
          indicator[cell->active_cell_index()] = std::sqrt(sum) / s;
        }
  }


  template <int dim>
  double
  stress_jump_estimate(const solid::Solid<dim> &solid,
                       const VectorType        &u_ghosted,
                       const double             time)
  {
    Vector<float> indicator;
    stress_jump_indicator(solid, u_ghosted, time, indicator);
    double sum = 0;
    for (const float eta : indicator)
      sum += double(eta) * eta;
    return std::sqrt(Utilities::MPI::sum(sum, parallel_tools::communicator()));
  }

  template void
  stress_jump_indicator(const solid::Solid<1> &,
                        const VectorType &,
                        const double,
                        Vector<float> &);
  template void
  stress_jump_indicator(const solid::Solid<2> &,
                        const VectorType &,
                        const double,
                        Vector<float> &);
  template void
  stress_jump_indicator(const solid::Solid<3> &,
                        const VectorType &,
                        const double,
                        Vector<float> &);
  template double
  stress_jump_estimate(const solid::Solid<1> &,
                       const VectorType &,
                       const double);
  template double
  stress_jump_estimate(const solid::Solid<2> &,
                       const VectorType &,
                       const double);
  template double
  stress_jump_estimate(const solid::Solid<3> &,
                       const VectorType &,
                       const double);
} // namespace tissuefem::adaptation


namespace tissuefem::adaptation
{
  /// stress_jump_indicator() as a registered refinement indicator.
  template <int dim>
  class StressJumpIndicator : public Indicator<dim>
  {
  public:
    void
    estimate(const solid::Solid<dim> &solid,
             const VectorType        &u_ghosted,
             const double             time,
             Vector<float>           &indicator) const override
    {
      stress_jump_indicator(solid, u_ghosted, time, indicator);
    }
  };
} // namespace tissuefem::adaptation

namespace
{
  using tissuefem::adaptation::StressJumpIndicator;
}
TISSUEFEM_REGISTER_INDICATOR(
  StressJumpIndicator,
  "stress jump",
  "the face terms of the residual error estimator, the jump of the "
  "traction P N across faces and its misfit on traction boundaries, scaled "
  "by 1/(2 mu) (adaptation/stress_jump.h): an estimate of the H1 seminorm "
  "error that weighs the force imbalance, so stiff and loaded regions "
  "count more than Kelly's gradient jumps say.")
