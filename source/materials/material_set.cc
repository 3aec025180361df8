#include <deal.II/base/utilities.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/materials/material_set.h>

#include <cmath>
#include <sstream>

namespace tissuefem::materials
{
  std::string
  tangent_method_pattern()
  {
    return "fastest|automatic differentiation|automatic differentiation in "
           "F|deal.II AD helper|hand coded";
  }


  TangentMethod
  parse_tangent_method(const std::string &name)
  {
    if (name == "automatic differentiation")
      return TangentMethod::automatic_differentiation;
    if (name == "automatic differentiation in F")
      return TangentMethod::automatic_differentiation_in_F;
    if (name == "deal.II AD helper")
      return TangentMethod::dealii_ad_helper;
    if (name == "fastest")
      return TangentMethod::fastest;
    require(name == "hand coded",
            "Materials/Tangent",
            "unknown method '" + name + "'");
    return TangentMethod::hand_coded;
  }


  ElasticConstants
  ElasticConstants::from_young_poisson(const double E, const double nu)
  {
    return {E * nu / ((1. + nu) * (1. - 2. * nu)), E / (2. * (1. + nu))};
  }


  void
  MaterialParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Materials");
    {
      prm.declare_entry(
        "Material ids",
        "",
        Patterns::List(Patterns::Integer(0, 255)),
        "The mesh material ids the lists below refer to, in order. Empty: one "
        "material for every cell whatever its id.");
      prm.declare_entry("Model",
                        "robust neo-Hookean",
                        Patterns::List(Patterns::Selection(
                          MaterialRegistry<3>::instance().selection_pattern())),
                        "The constitutive model per material id (or one for "
                        "all). "
                          + MaterialRegistry<3>::instance().documentation());
      prm.declare_entry("Elastic constants",
                        "Young's modulus and Poisson's ratio",
                        Patterns::Selection(
                          "Young's modulus and Poisson's ratio|Lame"),
                        "Which pair below defines the elastic constants.");
      prm.declare_entry("Young's modulus",
                        "1000",
                        Patterns::List(Patterns::Double()),
                        "Young's modulus E > 0 per material id, in units of "
                        "stress (Pa if SI).");
      prm.declare_entry("Poisson's ratio",
                        "0.3",
                        Patterns::List(Patterns::Double()),
                        "Poisson's ratio nu per material id, -1 < nu < 0.5 "
                        "(dimensionless).");
      prm.declare_entry("Lame lambda",
                        "576.923076923",
                        Patterns::List(Patterns::Double()),
                        "First Lame parameter per material id (stress units); "
                        "used when 'Elastic constants = Lame'.");
      prm.declare_entry("Lame mu",
                        "384.615384615",
                        Patterns::List(Patterns::Double()),
                        "Shear modulus mu > 0 per material id (stress units); "
                        "used when 'Elastic constants = Lame'.");
      prm.declare_entry("Density",
                        "1",
                        Patterns::List(Patterns::Double()),
                        "Mass density rho_0 > 0 per unit reference volume per "
                        "material id (kg/m^3 if SI).");
      prm.declare_entry(
        "Tangent",
        "fastest",
        Patterns::Selection(tangent_method_pattern()),
        "How stress and tangent dP/dF are obtained from the energy: "
        "'fastest' (default: 'hand coded' where the model has a closed form, "
        "else 'automatic differentiation'; the two agree to about 1e-14 "
        "relative, as tissuefem --check-material shows), "
        "'automatic differentiation' (fixed-size Sacado numbers; of Psi(I1, "
        "J) chained with closed-form invariant derivatives for models written "
        "in invariants, else of Psi(F)), 'automatic differentiation in F' "
        "(fixed-size Sacado in the entries of F for every model), 'deal.II AD "
        "helper' (deal.II's Differentiation::AD::ScalarFunction with dynamic "
        "Sacado numbers, slowest) or 'hand coded' (closed form; the "
        "neo-Hookean "
        "models, St Venant-Kirchhoff and its transversely isotropic variant).");
      prm.declare_entry(
        "Fibre direction",
        "1; 0; 0",
        Patterns::Anything(),
        "Reference fibre direction a for anisotropic models, 'a_x; a_y; a_z' "
        "as functions of x, y, z (the first Dimension of them are read); "
        "normalized to unit "
        "length at every quadrature point, and must not vanish there. Written "
        "to the VTU output as the cell fields fibre_x, fibre_y, fibre_z.");
      prm.declare_entry(
        "Tangent projection",
        "none",
        Patterns::Selection("none|positive definite"),
        "'positive definite': at every quadrature point the tangent dP/dF "
        "(a symmetric d^2 x d^2 matrix for an energy) has its eigenvalues "
        "raised to at least 1e-6 times the largest magnitude, so that the "
        "stiffness is positive semi-definite on any state, inverted or "
        "beyond a limit point, and Newton's updates descend the energy. "
        "Newton converges more slowly (linearly) where the exact tangent is "
        "indefinite. With 'Formulation = mean dilatation' only the material "
        "tangent at Fbar is projected, not the coupling through the cell's "
        "mean dilatation, so there it is no guarantee. 'none': the exact "
        "tangent.");
      // 'Formulation' is declared with the formulations that may be
      // chosen (solid/formulations/interface.h).
      MaterialRegistry<3>::instance().declare_parameters(prm);
    }
    prm.leave_subsection();
  }


  namespace
  {
    /// Reads a list parameter and expands a single value to @p n values.
    std::vector<std::string>
    read_list(ParameterHandler &prm, const std::string &name, const unsigned n)
    {
      std::vector<std::string> values
        = Utilities::split_string_list(prm.get(name));
      if (values.size() == 1)
        values.resize(n, values[0]);
      require(values.size() == n,
              "Materials/" + name,
              (n == 1 ? std::string("expected 1 value (one per entry of "
                                    "'Materials/Material ids', which is "
                                    "empty), got ")
                      : "expected 1 or " + std::to_string(n)
                          + " values (one per material id), got ")
                + std::to_string(values.size()));
      return values;
    }

    std::vector<double>
    read_doubles(ParameterHandler &prm, const std::string &name, unsigned n)
    {
      std::vector<double> result;
      for (const auto &v : read_list(prm, name, n))
        result.push_back(Utilities::string_to_double(v));
      return result;
    }
  } // namespace


  void
  MaterialParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Materials");
    material_ids.clear();
    for (const auto &id : Utilities::split_string_list(prm.get("Material ids")))
      material_ids.push_back(Utilities::string_to_int(id));
    const unsigned int n = std::max<std::size_t>(material_ids.size(), 1);

    model_names = read_list(prm, "Model", n);
    densities   = read_doubles(prm, "Density", n);
    for (const double rho : densities)
      require(rho > 0 && std::isfinite(rho),
              "Materials/Density",
              "must be > 0, got " + std::to_string(rho));

    constants.clear();
    if (prm.get("Elastic constants") == "Lame")
      {
        const auto lambda = read_doubles(prm, "Lame lambda", n);
        const auto mu     = read_doubles(prm, "Lame mu", n);
        for (unsigned int i = 0; i < n; ++i)
          {
            require(mu[i] > 0,
                    "Materials/Lame mu",
                    "must be > 0, got " + std::to_string(mu[i]));
            // A positive bulk modulus in 3D: lambda + 2 mu / 3 > 0.
            require(lambda[i] + 2. * mu[i] / 3. > 0,
                    "Materials/Lame lambda",
                    "must exceed -2 mu / 3, got " + std::to_string(lambda[i]));
            constants.push_back({lambda[i], mu[i]});
          }
      }
    else
      {
        const auto E  = read_doubles(prm, "Young's modulus", n);
        const auto nu = read_doubles(prm, "Poisson's ratio", n);
        for (unsigned int i = 0; i < n; ++i)
          {
            require(E[i] > 0 && std::isfinite(E[i]),
                    "Materials/Young's modulus",
                    "must be > 0, got " + std::to_string(E[i]));
            require(nu[i] > -1 && nu[i] < 0.5,
                    "Materials/Poisson's ratio",
                    "must satisfy -1 < nu < 0.5, got " + std::to_string(nu[i]));
            constants.push_back(
              ElasticConstants::from_young_poisson(E[i], nu[i]));
          }
      }
    tangent_method  = parse_tangent_method(prm.get("Tangent"));
    fibre_direction = prm.get("Fibre direction");
    formulation     = prm.get("Formulation");
    project_tangent = prm.get("Tangent projection") == "positive definite";
    prm.leave_subsection();
  }


  template <int dim>
  MaterialSet<dim>::MaterialSet(const MaterialParameters &parameters,
                                const ParameterHandler   &prm)
      : method(parameters.tangent_method)
      , fibre(make_function<dim>(
          leading_entries(parameters.fibre_direction, ';', dim),
          dim,
          "Materials/Fibre direction"))
      , formulation_name(parameters.formulation)
      , project(parameters.project_tangent)
  {
    for (unsigned int i = 0; i < parameters.model_names.size(); ++i)
      {
        const types::material_id key = parameters.material_ids.empty()
                                         ? numbers::invalid_material_id
                                         : parameters.material_ids[i];
        Entry                    entry{MaterialRegistry<dim>::instance().create(
                      parameters.model_names[i], parameters.constants[i], prm),
                    parameters.densities[i],
                    parameters.model_names[i]};
        require(method != TangentMethod::hand_coded
                  || entry.model->has_hand_coded_tangent(),
                "Materials/Tangent",
                "'hand coded' is not available for model '"
                  + parameters.model_names[i] + "'");
        entries[key] = std::move(entry);
      }
  }


  template <int dim>
  void
  MaterialSet<dim>::check_covers(const Triangulation<dim> &triangulation) const
  {
    if (entries.count(numbers::invalid_material_id))
      return;
    for (const auto &cell : triangulation.active_cell_iterators())
      require(entries.count(cell->material_id()) > 0,
              "Materials/Material ids",
              "the mesh has cells with material id "
                + std::to_string(cell->material_id())
                + ", which is not listed");
  }


  template <int dim>
  const typename MaterialSet<dim>::Entry &
  MaterialSet<dim>::entry(const types::material_id id) const
  {
    const auto all = entries.find(numbers::invalid_material_id);
    if (all != entries.end())
      return all->second;
    return entries.at(id);
  }


  template <int dim>
  const Interface<dim> &
  MaterialSet<dim>::material(const types::material_id id) const
  {
    return *entry(id).model;
  }


  template <int dim>
  double
  MaterialSet<dim>::density(const types::material_id id) const
  {
    return entry(id).density;
  }


  template <int dim>
  bool
  MaterialSet<dim>::any_uses_fibres() const
  {
    for (const auto &[id, e] : entries)
      if (e.model->uses_fibres())
        return true;
    return false;
  }


  template <int dim>
  Tensor<1, dim>
  MaterialSet<dim>::fibre_direction(const Point<dim> &X) const
  {
    Vector<double> value(dim);
    fibre->vector_value(X, value);
    Tensor<1, dim> a;
    for (unsigned int d = 0; d < dim; ++d)
      a[d] = value[d];
    const double length = a.norm();
    if (!(length > 1e-12 && std::isfinite(length)))
      {
        std::ostringstream where;
        where << X;
        throw InputError("Parameter 'Materials/Fibre direction': the "
                         "direction vanishes or is not finite at ("
                         + where.str() + ")");
      }
    return a / length;
  }

  template class MaterialSet<1>;
  template class MaterialSet<2>;
  template class MaterialSet<3>;
} // namespace tissuefem::materials
