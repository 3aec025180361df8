#pragma once

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/grid/tria.h>

#include <tissuefem/materials/interface.h>

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace tissuefem::materials
{
  /**
   * The 'Materials' subsection: which model, elastic constants and density
   * each material id of the mesh gets, and how tangents are computed.
   * Entries are lists with one value per listed material id, or a single
   * value that applies to all of them.
   */
  struct MaterialParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    std::vector<unsigned int>     material_ids;
    std::vector<std::string>      model_names;
    std::vector<ElasticConstants> constants;
    std::vector<double>           densities;
    TangentMethod                 tangent_method;
    std::string                   fibre_direction;
    /// 'Formulation' (declared by solid/formulations/interface.h).
    std::string formulation;
    bool        project_tangent;
  };

  template <int dim>
  class MaterialSet
  {
  public:
    MaterialSet(const MaterialParameters &parameters,
                const ParameterHandler   &prm);

    /// Throws InputError if a cell of @p triangulation has a material id no
    /// material is given for.
    void
    check_covers(const Triangulation<dim> &triangulation) const;

    const Interface<dim> &
    material(const types::material_id id) const;

    /// Mass density per unit reference volume (kg/m^3 if SI).
    double
    density(const types::material_id id) const;

    TangentMethod
    tangent_method() const
    {
      return method;
    }

    /// Whether any material depends on the fibre direction.
    bool
    any_uses_fibres() const;

    /// The unit fibre direction at reference point @p X (the 'Fibre
    /// direction' expression, normalized). Throws InputError where the
    /// expression vanishes.
    Tensor<1, dim>
    fibre_direction(const Point<dim> &X) const;

    /// The element formulation's registered name ('Materials/Formulation':
    /// solid/formulations/).
    const std::string &
    formulation() const
    {
      return formulation_name;
    }

    /// Every model of the set, with its registered name.
    std::vector<std::pair<std::string, const Interface<dim> *>>
    models() const
    {
      std::vector<std::pair<std::string, const Interface<dim> *>> result;
      for (const auto &[id, entry] : entries)
        result.emplace_back(entry.name, entry.model.get());
      return result;
    }

    /// Whether tangents are projected to positive definite ones
    /// (tangent_projection.h).
    bool
    project_tangent() const
    {
      return project;
    }

  private:
    struct Entry
    {
      std::unique_ptr<Interface<dim>> model;
      double                          density;
      std::string                     name;
    };
    /// Either keyed by material id, or a single entry for all cells (key
    /// numbers::invalid_material_id).
    std::map<types::material_id, Entry>  entries;
    TangentMethod                        method;
    std::unique_ptr<FunctionParser<dim>> fibre;
    std::string                          formulation_name;
    bool                                 project;

    const Entry &
    entry(const types::material_id id) const;
  };
} // namespace tissuefem::materials
