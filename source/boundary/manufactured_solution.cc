#include <tissuefem/base/input_error.h>
#include <tissuefem/boundary/manufactured_solution.h>

#include <cmath>
#include <functional>

namespace tissuefem::boundary
{
  void
  ManufacturedParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Manufactured solution");
    prm.declare_entry(
      "Enabled",
      "false",
      Patterns::Bool(),
      "Replace the scene's boundary conditions, loads and initial state by "
      "those of the manufactured displacement u_i = A sin(omega t + 0.4 i) "
      "prod_d cos(k X_d + 0.3 + 0.5 i + 0.2 d) (the whole boundary held at "
      "u, the body force that makes u exact), and report the error of the "
      "run against u in the L2 norm and H1 seminorm. Needs one isotropic "
      "material and no integrator damping.");
    prm.declare_entry("Amplitude",
                      "0.1",
                      Patterns::Double(0.),
                      "A (length units).");
    prm.declare_entry("Angular frequency",
                      "3",
                      Patterns::Double(0.),
                      "omega (radians per time unit); 0 gives a static u.");
    prm.declare_entry("Wave number",
                      "1.5",
                      Patterns::Double(0.),
                      "k (radians per length unit).");
    prm.leave_subsection();
  }


  void
  ManufacturedParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Manufactured solution");
    enabled           = prm.get_bool("Enabled");
    amplitude         = prm.get_double("Amplitude");
    angular_frequency = prm.get_double("Angular frequency");
    wave_number       = prm.get_double("Wave number");
    prm.leave_subsection();
  }


  namespace
  {
    /// A vector-valued Function<dim> of (X, t) from a closure.
    template <int dim>
    class FieldFunction : public Function<dim>
    {
    public:
      using Field = std::function<Tensor<1, dim>(const Point<dim> &, double)>;
      explicit FieldFunction(Field field)
          : Function<dim>(dim)
          , field(std::move(field))
      {
      }

      double
      value(const Point<dim> &X, const unsigned int component) const override
      {
        return field(X, this->get_time())[component];
      }

      void
      vector_value(const Point<dim> &X, Vector<double> &values) const override
      {
        const Tensor<1, dim> f = field(X, this->get_time());
        for (unsigned int d = 0; d < dim; ++d)
          values[d] = f[d];
      }

    private:
      Field field;
    };


    double
    phi(const unsigned int i)
    {
      return 0.4 * i;
    }


    double
    psi(const unsigned int i, const unsigned int d)
    {
      return 0.3 + 0.5 * i + 0.2 * d;
    }
  } // namespace


  template <int dim>
  ManufacturedSolution<dim>::ManufacturedSolution(
    const ManufacturedParameters      &parameters,
    const materials::MaterialSet<dim> &materials,
    const Triangulation<dim>          &triangulation,
    const bool                         with_inertia)
      : parameters(parameters)
      , material(
          materials.material(triangulation.begin_active()->material_id()))
      , density(materials.density(triangulation.begin_active()->material_id()))
      , tangent_method(materials.tangent_method())
      , inertia(with_inertia)
      , boundary_ids(triangulation.get_boundary_ids())
  {
    const auto id = triangulation.begin_active()->material_id();
    for (const auto &cell : triangulation.active_cell_iterators())
      require(cell->material_id() == id,
              "Manufactured solution/Enabled",
              "needs one material id in the whole mesh (the body force is "
              "computed for one material)");
    require(!materials.any_uses_fibres(),
            "Manufactured solution/Enabled",
            "does not support fibre-reinforced materials");
  }


  template <int dim>
  double
  ManufacturedSolution<dim>::phase(const unsigned int i, const double t) const
  {
    return std::sin(parameters.angular_frequency * t + phi(i));
  }


  template <int dim>
  double
  ManufacturedSolution<dim>::space(const unsigned int i,
                                   const Point<dim>  &X,
                                   const unsigned int dx1,
                                   const unsigned int dx2) const
  {
    // Derivatives of cos(theta) in X_d of order 0, 1, 2:
    // cos, -k sin, -k^2 cos.
    const double k       = parameters.wave_number;
    double       product = 1;
    for (unsigned int d = 0; d < dim; ++d)
      {
        const double       theta = k * X[d] + psi(i, d);
        const unsigned int order = (dx1 == d) + (dx2 == d);
        product *= order == 0   ? std::cos(theta)
                   : order == 1 ? -k * std::sin(theta)
                                : -k * k * std::cos(theta);
      }
    return product;
  }


  template <int dim>
  Tensor<1, dim>
  ManufacturedSolution<dim>::displacement(const Point<dim> &X,
                                          const double      t) const
  {
    Tensor<1, dim> u;
    for (unsigned int i = 0; i < dim; ++i)
      u[i] = parameters.amplitude * phase(i, t) * space(i, X, dim, dim);
    return u;
  }


  template <int dim>
  Tensor<1, dim>
  ManufacturedSolution<dim>::velocity(const Point<dim> &X, const double t) const
  {
    const double   omega = parameters.angular_frequency;
    Tensor<1, dim> v;
    for (unsigned int i = 0; i < dim; ++i)
      v[i] = parameters.amplitude * omega * std::cos(omega * t + phi(i))
             * space(i, X, dim, dim);
    return v;
  }


  template <int dim>
  Tensor<2, dim>
  ManufacturedSolution<dim>::gradient(const Point<dim> &X, const double t) const
  {
    Tensor<2, dim> G;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        G[i][j] = parameters.amplitude * phase(i, t) * space(i, X, j, dim);
    return G;
  }


  template <int dim>
  Tensor<1, dim>
  ManufacturedSolution<dim>::body_force(const Point<dim> &X,
                                        const double      t) const
  {
    const Tensor<2, dim> F = unit_symmetric_tensor<dim>() + gradient(X, t);
    Tensor<2, dim>       P;
    Tensor<4, dim>       A;
    material.stress_and_tangent(F, Tensor<1, dim>(), P, A, tangent_method);
    // Div P_i = A_ijkl dF_kl/dX_j, dF_kl/dX_j = d^2 u_k / dX_l dX_j.
    Tensor<3, dim> grad_F;
    for (unsigned int k = 0; k < dim; ++k)
      for (unsigned int l = 0; l < dim; ++l)
        for (unsigned int j = 0; j < dim; ++j)
          grad_F[k][l][j]
            = parameters.amplitude * phase(k, t) * space(k, X, l, j);
    Tensor<1, dim> b;
    const double   omega2
      = parameters.angular_frequency * parameters.angular_frequency;
    for (unsigned int i = 0; i < dim; ++i)
      {
        double div_P = 0;
        for (unsigned int j = 0; j < dim; ++j)
          for (unsigned int k = 0; k < dim; ++k)
            for (unsigned int l = 0; l < dim; ++l)
              div_P += A[i][j][k][l] * grad_F[k][l][j];
        // u_tt = -omega^2 u.
        const double u_tt = inertia ? -omega2 * parameters.amplitude
                                        * phase(i, t) * space(i, X, dim, dim)
                                    : 0.;
        b[i]              = density * u_tt - div_P;
      }
    return b;
  }


  template <int dim>
  void
  ManufacturedSolution<dim>::impose_on(BoundaryConditions<dim> &c) const
  {
    const auto field = [this](auto member) {
      return std::make_unique<FieldFunction<dim>>(
        [this, member](const Point<dim> &X, const double t) {
          return (this->*member)(X, t);
        });
    };
    c.dirichlet.clear();
    for (const auto id : boundary_ids)
      c.dirichlet.push_back({id,
                             ComponentMask(dim, true),
                             field(&ManufacturedSolution::displacement)});
    c.neumann.clear();
    c.body_force           = field(&ManufacturedSolution::body_force);
    c.body_force_is_zero   = false;
    c.gravity              = Tensor<1, dim>();
    c.initial_displacement = field(&ManufacturedSolution::displacement);
    c.initial_velocity     = field(&ManufacturedSolution::velocity);
  }


  template class ManufacturedSolution<1>;
  template class ManufacturedSolution<2>;
  template class ManufacturedSolution<3>;
} // namespace tissuefem::boundary
