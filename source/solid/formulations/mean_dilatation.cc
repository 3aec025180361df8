#include <tissuefem/base/moved_entries.h>
#include <tissuefem/materials/kinematics.h>
#include <tissuefem/materials/tangent_projection.h>
#include <tissuefem/solid/formulations/mean_dilatation.h>
#include <tissuefem/solid/mean_dilatation.h>

namespace tissuefem::solid::formulations
{
  namespace
  {
    /// Per shape function dtheta/du (b) and sum_q w_q phi_Ftheta g (C),
    /// and Theta = sum_q w_q phi_theta_theta (mean_dilatation.h).
    template <int dim>
    struct MeanScratch : public Scratch
    {
      explicit MeanScratch(const unsigned int n_scalar)
          : b(n_scalar)
          , C(n_scalar)
      {
      }
      std::unique_ptr<Scratch>
      clone() const override
      {
        return std::make_unique<MeanScratch>(*this);
      }
      std::vector<Tensor<1, dim>> b, C;
      double                      Theta = 0;
    };

    template <int dim>
    MeanScratch<dim> &
    own(CellTerms<dim> &cell)
    {
      return static_cast<MeanScratch<dim> &>(*cell.own);
    }

    /// Fbar of the cells' mean dilatation, scaled by the carried factor of
    /// @p carry_time where given.
    template <int dim>
    class MeanDeformation : public Deformation<dim>
    {
    public:
      MeanDeformation(const DilatationCarry<dim> &carried,
                      const double               *carry_time)
          : carried(carried)
          , carry_time(carry_time)
      {
      }

      bool
      apply(const typename DoFHandler<dim>::active_cell_iterator &cell,
            std::vector<Tensor<2, dim>>                          &F,
            const double                                         *JxW,
            const unsigned int n) const override
      {
        return apply_mean_dilatation(
          F,
          JxW,
          n,
          carry_time ? carried.factor(cell->active_cell_index(), *carry_time)
                     : 1.);
      }

    private:
      const DilatationCarry<dim> &carried;
      const double               *carry_time;
    };
  } // namespace


  template <int dim>
  void
  MeanDilatation<dim>::declare_parameters(ParameterHandler &prm)
  {
    moved_entries::declare(
      prm,
      "Newton solver/Mean dilatation update",
      "Materials/Mean dilatation/Update",
      "three-field",
      Patterns::Selection("three-field|condensed"),
      "How implicit steps iterate the mean dilatation (F-bar) element "
      "('Materials/Formulation = mean dilatation'); the converged answer "
      "is the same. 'three-field': each cell's dilatation and pressure "
      "are Newton unknowns of their own, updated linearly with the "
      "displacement and condensed per cell (the Hu-Washizu form of Simo, "
      "Taylor and Pister 1985, as in deal.II's step-44), and Newton "
      "takes full steps, shortened only where a trial state cannot be "
      "evaluated (off the constraint the energy is no merit). "
      "'condensed': they are recomputed from the displacement at every "
      "iterate, where a nearly incompressible material turns a Newton "
      "step's second-order error in the dilatation into pressures of bulk "
      "modulus times it. Measured on parameters/cook_membrane.prm (nu = "
      "0.4999): 4-5 iterations per load step against 11-13, the whole load "
      "in one step (condensed: 108 iterations, two halvings), and adaptive "
      "runs without step halvings. A mesh change's carried dilatation "
      "(DilatationCarry) is then the first iterate of the next step; "
      "'Release steps' acts with 'condensed' only. Integrators other than "
      "backward Euler and quasistatic use the condensed element; the "
      "quasi-Newton backward Euler needs 'condensed'.");
    moved_entries::declare(
      prm,
      "Mesh refinement/Dilatation release steps",
      "Materials/Mean dilatation/Release steps",
      "1",
      Patterns::Double(0, 1000),
      "With an adaptive mesh: each cell of a changed mesh starts with the "
      "volume change (cell mean of det F) of the cell it came from, so "
      "that refining a nearly incompressible body does not create "
      "pressure jumps of the bulk modulus times the variation of det F "
      "inside the old cell. With 'Update = three-field' (default) that is "
      "the first iterate of the cell dilatations in the next step, which "
      "then solves the new mesh's equations, and this entry only says "
      "whether to carry (0: not). With 'condensed' the cell's own volume "
      "change is phased in linearly over this many times 'Time "
      "integration/Time step' of simulated time (a halved step faces half "
      "the change). Only the implicit integrators' equations see the "
      "carried part; outputs show the material itself. 0: a new cell has "
      "its own volume change at once.");
  }


  template <int dim>
  MeanDilatation<dim>::MeanDilatation(ParameterHandler &prm)
  {
    prm.enter_subsection("Materials");
    prm.enter_subsection("Mean dilatation");
    three_field_update    = prm.get("Update") == "three-field";
    carried.release_steps = prm.get_double("Release steps");
    prm.leave_subsection();
    prm.leave_subsection();
  }


  template <int dim>
  void
  MeanDilatation<dim>::check(const Discretization<dim> &discretization,
                             const materials::MaterialSet<dim> &) const
  {
    require(!(discretization.simplex && discretization.fe->degree == 1),
            "Materials/Formulation",
            "'mean dilatation' changes nothing on linear simplices (their F "
            "is constant per cell); use Polynomial degree = 2 (the P2-P0 "
            "element) or a hexahedral mesh");
  }


  template <int dim>
  std::unique_ptr<Scratch>
  MeanDilatation<dim>::make_scratch(const Context<dim> &context) const
  {
    return std::make_unique<MeanScratch<dim>>(context.cache.n_scalar);
  }


  template <int dim>
  std::pair<double, double>
  MeanDilatation<dim>::point_terms(const Context<dim> &context,
                                   CellTerms<dim>     &cell,
                                   const double        theta,
                                   const bool          linearize) const
  {
    const auto        &cache = context.cache;
    const unsigned int n_q = cache.n_q, n_scalar = cache.n_scalar;
    const double      *JxW    = cache.JxW(cell.c);
    const auto         method = context.materials.tangent_method();
    auto              &s      = own(cell);
    double             volume = 0, Phi_theta = 0;
    s.Theta = 0;
    for (unsigned int k = 0; k < n_scalar; ++k)
      s.b[k] = s.C[k] = Tensor<1, dim>();
    MeanDilatationPoint<dim> point;
    Tensor<2, dim>           P_bar;
    Tensor<4, dim>           A_bar;
    for (unsigned int q = 0; q < n_q; ++q)
      {
        const Tensor<2, dim> F_bar
          = modified_deformation_gradient(cell.F[q], theta);
        const Tensor<1, dim> &a = context.fibres.at(cell.index, q);
        if (linearize)
          {
            cell.material->stress_and_tangent(F_bar, a, P_bar, A_bar, method);
            if (context.materials.project_tangent())
              materials::project_to_positive_definite(A_bar);
            mean_dilatation_stress_and_tangent(
              cell.F[q], theta, P_bar, A_bar, point);
            cell.A[q] = point.phi_FF;
            s.Theta += JxW[q] * point.phi_theta_theta;
            const Tensor<2, dim> cof = cofactor(cell.F[q]);
            for (unsigned int k = 0; k < n_scalar; ++k)
              {
                const Tensor<1, dim> &g = cache.gradient(cell.c, q, k);
                s.C[k] += JxW[q] * (point.phi_F_theta * g);
                s.b[k] += JxW[q] * (cof * g);
              }
          }
        else
          mean_dilatation_stress(cell.F[q],
                                 theta,
                                 cell.material->stress(F_bar, a),
                                 point);
        cell.P[q] = point.phi_F;
        Phi_theta += JxW[q] * point.phi_theta;
        volume += JxW[q];
      }
    for (unsigned int k = 0; k < n_scalar; ++k)
      s.b[k] /= volume;
    return {volume, Phi_theta};
  }


  template <int dim>
  bool
  MeanDilatation<dim>::cell_terms(const Context<dim> &context,
                                  CellTerms<dim>     &cell) const
  {
    // The element checks its points itself: Fbar needs det F > 0 at each.
    deformation_gradients(context.cache, cell);
    if (three_field.active())
      three_field_cell(context, cell);
    else
      condensed_cell(context, cell);
    return true;
  }


  template <int dim>
  void
  MeanDilatation<dim>::condensed_cell(const Context<dim> &context,
                                      CellTerms<dim>     &cell) const
  {
    const auto  &cache = context.cache;
    const double mean
      = solid::mean_dilatation(cell.F, cache.JxW(cell.c), cache.n_q);
    if (mean <= 0)
      {
        cell.inverted_det = mean;
        return;
      }
    // A carried dilatation scales theta by a constant: dtheta/du (b) and
    // the pressure-like term scale with it, Theta and C do not.
    const double factor
      = cell.carry_time ? carried.factor(cell.index, *cell.carry_time) : 1.;
    const auto [volume, Phi_theta]
      = point_terms(context, cell, factor * mean, cell.jacobian);
    auto &s = own(cell);
    for (unsigned int k = 0; k < cache.n_scalar; ++k)
      s.b[k] *= factor;
    // The pressure-like term Phi_theta/V couples every point through
    // theta: its first derivative is cof F_q, its second dcof/dF.
    add_cell_pressure(factor * Phi_theta / volume, cell);
  }


  template <int dim>
  void
  MeanDilatation<dim>::three_field_cell(const Context<dim> &context,
                                        CellTerms<dim>     &cell) const
  {
    const auto        &cache = context.cache;
    const unsigned int c     = cell.c;
    const double mean = solid::mean_dilatation(cell.F, cache.JxW(c), cache.n_q);
    // The first assembly of a step sets the unknowns: the carried
    // dilatation of a changed cell (the old mesh's, so that its pressure
    // is the old one and the momentum rows start balanced), else the
    // cell's own; the pressure consistent with it.
    if (three_field.initializing() && mean > 0)
      three_field.theta(c) = mean * carried.factor(cell.index, start);
    const double theta = three_field.theta(c);
    if (mean <= 0 || theta <= 0)
      {
        cell.inverted_det = std::min(mean, theta);
        return;
      }
    // The cell's b, C and Theta are those of the last Jacobian, so that
    // modified Newton ('Jacobian reuse') condenses with the matrix it
    // solves with.
    const bool linearize = cell.jacobian || !three_field.linearized(c);
    const auto [volume, Phi_theta]
      = point_terms(context, cell, theta, linearize);
    if (three_field.initializing())
      three_field.pressure(c) = Phi_theta / volume;
    const double pressure = three_field.pressure(c);
    add_cell_pressure(pressure, cell);
    if (linearize)
      {
        const auto         &s = own(cell);
        std::vector<double> b(cache.n_dofs), C(cache.n_dofs);
        for (unsigned int k = 0; k < cache.n_scalar; ++k)
          for (unsigned int a = 0; a < dim; ++a)
            {
              b[cache.local_index[k * dim + a]] = s.b[k][a];
              C[cache.local_index[k * dim + a]] = s.C[k][a];
            }
        three_field.set_linearization(
          c, std::move(b), std::move(C), s.Theta, volume);
      }
    three_field.add_condensed_rows(c,
                                   mean - theta,
                                   Phi_theta - pressure * volume,
                                   *cell.rhs);
  }


  template <int dim>
  void
  MeanDilatation<dim>::add_cell_pressure(const double    pressure,
                                         CellTerms<dim> &cell) const
  {
    for (unsigned int q = 0; q < cell.F.size(); ++q)
      {
        cell.P[q] += pressure * cofactor(cell.F[q]);
        if (cell.jacobian)
          materials::add_cofactor_derivative(cell.F[q], pressure, cell.A[q]);
      }
  }


  template <int dim>
  void
  MeanDilatation<dim>::add_cell_rows(const Context<dim> &context,
                                     CellTerms<dim>     &cell) const
  {
    if (!cell.jacobian)
      return;
    // The rank-two terms that couple every point through theta
    // (mean_dilatation.h).
    const auto         &cache    = context.cache;
    const unsigned int  n_scalar = cache.n_scalar;
    const auto         &s        = own(cell);
    FullMatrix<double> &matrix   = *cell.matrix;
    for (unsigned int k = 0; k < n_scalar; ++k)
      for (unsigned int a = 0; a < dim; ++a)
        {
          const unsigned int i = cache.local_index[k * dim + a];
          for (unsigned int l = 0; l < n_scalar; ++l)
            for (unsigned int b = 0; b < dim; ++b)
              {
                const unsigned int j = cache.local_index[l * dim + b];
                if (j >= i)
                  matrix(i, j) += s.C[k][a] * s.b[l][b] + s.b[k][a] * s.C[l][b]
                                  + s.Theta * s.b[k][a] * s.b[l][b];
              }
        }
  }


  template <int dim>
  void
  MeanDilatation<dim>::assembled()
  {
    if (three_field.active())
      three_field.initialized();
  }


  template <int dim>
  std::unique_ptr<Deformation<dim>>
  MeanDilatation<dim>::deformation(const Context<dim> &,
                                   const VectorType &,
                                   const double *carry_time) const
  {
    return std::make_unique<MeanDeformation<dim>>(carried, carry_time);
  }


  template <int dim>
  std::string
  MeanDilatation<dim>::inversion_advice() const
  {
    return "the mean dilatation formulation needs det F > 0 at every "
           "quadrature point (its Fbar = (theta/J)^(1/d) F); use "
           "'Formulation = displacement' with an invertible model for "
           "scenes that invert elements";
  }


  template <int dim>
  void
  MeanDilatation<dim>::begin_iterations(const double start_time)
  {
    three_field.begin(cache->cells().size());
    start = start_time;
  }


  template <int dim>
  void
  MeanDilatation<dim>::predict_update(const VectorType &du)
  {
    std::vector<double> du_cell(cache->n_dofs);
    for (unsigned int c = 0; c < cache->cells().size(); ++c)
      {
        const types::global_dof_index *dofs = cache->dofs(c);
        for (unsigned int i = 0; i < cache->n_dofs; ++i)
          du_cell[i] = du[dofs[i]];
        three_field.predict(c, du_cell);
      }
  }


  template <int dim>
  void
  MeanDilatation<dim>::set_step_length(const double alpha)
  {
    three_field.trial(alpha);
  }


  template <int dim>
  void
  MeanDilatation<dim>::end_iterations(const bool converged)
  {
    three_field.end();
    // A carried dilatation is the first iterate of the step after a mesh
    // change; once a step has converged on the new mesh it has served
    // (a retried step starts from it again).
    if (converged)
      carried.clear();
  }


  template class MeanDilatation<1>;
  template class MeanDilatation<2>;
  template class MeanDilatation<3>;

  TISSUEFEM_REGISTER_FORMULATION(
    MeanDilatation,
    "mean dilatation",
    "the F-bar form of the three-field Q1-P0 element (Simo, Taylor and "
    "Pister 1985; de Souza Neto et al. 1996): Psi is evaluated at Fbar = "
    "(theta/J)^(1/d) F with theta the cell mean of J, which removes "
    "volumetric locking of nearly incompressible materials on "
    "quadrilaterals/hexahedra (Q1-P0, Q2-P0) and on P2 triangles/tetrahedra "
    "(P2-P0); it changes nothing on P1 simplices (constant F), where it is "
    "refused.")
} // namespace tissuefem::solid::formulations
