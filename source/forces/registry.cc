#include <tissuefem/base/input_error.h>
#include <tissuefem/forces/registry.h>

#include <algorithm>

namespace tissuefem::forces
{
  std::string
  integrators_with(bool Capabilities::*has)
  {
    // Every registered integrator is built once, with its defaults: only
    // for a message.
    ParameterHandler defaults;
    time::TimeParameters::declare_parameters(defaults);
    std::vector<std::string> names;
    for (const auto &[name, entry] : time::IntegratorRegistry::instance().all())
      if (entry.create(defaults)->capabilities().*has)
        names.push_back(name);
    std::string list;
    for (unsigned int i = 0; i < names.size(); ++i)
      list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    return list;
  }


  template <int dim>
  void
  SceneData<dim>::refuse_unless(bool Capabilities::*needed,
                                const std::string  &parameter,
                                const std::string  &what,
                                const std::string  &why) const
  {
    if (can.*needed)
      return;
    throw InputError("Parameter '" + parameter + "': " + what
                     + " Time integration/Integrator = "
                     + integrators_with(needed) + " (not '" + integrator + "'"
                     + (why.empty() ? "" : ": " + why) + ")");
  }


  template <int dim>
  double
  SceneData<dim>::largest_youngs_modulus() const
  {
    double modulus = 0;
    for (const auto &c : materials.constants)
      modulus = std::max(modulus,
                         c.mu * (3 * c.lambda + 2 * c.mu) / (c.lambda + c.mu));
    return modulus;
  }


  template struct SceneData<1>;
  template struct SceneData<2>;
  template struct SceneData<3>;
} // namespace tissuefem::forces
