#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <tissuefem/base/input_error.h>

#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <type_traits>

namespace tissuefem
{
  /**
   * A table of named implementations of one interface (materials, time
   * integrators, problems, ...). Each implementation adds itself from its own
   * source file through a static Registrar object, so the list of choices a
   * parameter file may name is generated from what is compiled in, and adding
   * an implementation touches no central list.
   *
   * @p Interface is the base class; @p Factory is the signature of the
   * function that creates one, e.g.
   * std::unique_ptr<Interface>(const ParameterHandler &).
   */
  template <typename Interface, typename... FactoryArguments>
  class Registry
  {
  public:
    using Factory
      = std::function<std::unique_ptr<Interface>(FactoryArguments...)>;
    using Declarer = std::function<void(dealii::ParameterHandler &)>;

    struct Entry
    {
      std::string description;
      Declarer    declare_parameters;
      Factory     create;
    };

    /// The single table for this interface.
    static Registry &
    instance()
    {
      static Registry registry;
      return registry;
    }

    void
    add(const std::string &name,
        const std::string &description,
        const Declarer    &declarer,
        const Factory     &factory)
    {
      entries[name] = Entry{description, declarer, factory};
    }

    /**
     * Accepts @p old_name, an earlier spelling, for @p name, so that
     * users' parameter files keep working after a registered name was
     * recased; canonical() names the new spelling in a notice.
     */
    void
    add_alias(const std::string &old_name, const std::string &name)
    {
      aliases[old_name] = name;
    }

    /**
     * Accepts @p synonym for @p name silently and for good (e.g. a
     * generic default such as 'direct' standing for one implementation);
     * canonical() returns @p name.
     */
    void
    add_synonym(const std::string &synonym, const std::string &name)
    {
      synonyms[synonym] = name;
    }

    /// Names separated by '|', for a Patterns::Selection: the registered
    /// ones, their synonyms and the earlier spellings still accepted.
    std::string
    selection_pattern() const
    {
      std::string result;
      for (const auto &[name, entry] : entries)
        result += (result.empty() ? "" : "|") + name;
      for (const auto &[synonym, name] : synonyms)
        result += "|" + synonym;
      for (const auto &[old_name, name] : aliases)
        result += "|" + old_name;
      return result;
    }

    /**
     * The registered name for @p name: itself, or the name an earlier
     * spelling stands for, with a one-line notice on stderr (process 0)
     * naming @p parameter and the new spelling.
     */
    std::string
    canonical(const std::string &name, const std::string &parameter) const
    {
      if (const auto synonym = synonyms.find(name); synonym != synonyms.end())
        return synonym->second;
      const auto alias = aliases.find(name);
      if (alias == aliases.end())
        return name;
      if (noticed.insert(name).second
          && dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
        std::cerr << "tissuefem: notice: " << parameter << " = '" << name
                  << "' is now spelled '" << alias->second
                  << "'; the old spelling is still accepted." << std::endl;
      return alias->second;
    }

    /// One line per choice: "name: description", for parameter
    /// documentation; then the earlier spellings still accepted.
    std::string
    documentation() const
    {
      std::string result;
      for (const auto &[name, entry] : entries)
        result += "'" + name + "': " + entry.description + " ";
      for (const auto &[synonym, name] : synonyms)
        result += "'" + synonym + "': the same as '" + name + "'. ";
      for (const auto &[old_name, name] : aliases)
        result
          += "('" + old_name + "': the earlier spelling of '" + name + "'.) ";
      return result;
    }

    /// Lets every registered implementation declare its own parameters.
    void
    declare_parameters(dealii::ParameterHandler &prm) const
    {
      for (const auto &[name, entry] : entries)
        if (entry.declare_parameters)
          entry.declare_parameters(prm);
    }

    std::unique_ptr<Interface>
    create(const std::string &name, FactoryArguments... arguments) const
    {
      auto it = entries.find(name);
      if (it == entries.end())
        if (const auto synonym = synonyms.find(name); synonym != synonyms.end())
          it = entries.find(synonym->second);
      if (it == entries.end())
        if (const auto alias = aliases.find(name); alias != aliases.end())
          it = entries.find(alias->second);
      if (it == entries.end())
        throw InputError("'" + name + "' is not a known choice; known are: "
                         + selection_pattern());
      return it->second.create(arguments...);
    }

    const std::map<std::string, Entry> &
    all() const
    {
      return entries;
    }

  private:
    std::map<std::string, Entry> entries;
    /// Earlier spelling -> registered name.
    std::map<std::string, std::string> aliases;
    /// Synonym -> registered name.
    std::map<std::string, std::string> synonyms;
    /// Earlier spellings already named in a notice (one notice each).
    mutable std::set<std::string> noticed;
  };


  /**
   * Adds @p Class<dim> (default-constructible, deriving from
   * @p Interface<dim>) under @p name to Registry<Interface<dim>> for dim =
   * 1, 2, 3: the registration of plugins that take no parameters of their
   * own (refinement indicators, geometry sources).
   */
  template <template <int> class Interface, template <int> class Class>
  bool
  register_in_every_dimension(const std::string &name,
                              const std::string &description)
  {
    auto add = [&](auto dim_tag) {
      constexpr int dim = decltype(dim_tag)::value;
      Registry<Interface<dim>>::instance().add(name, description, {}, []() {
        return std::unique_ptr<Interface<dim>>(std::make_unique<Class<dim>>());
      });
    };
    add(std::integral_constant<int, 1>());
    add(std::integral_constant<int, 2>());
    add(std::integral_constant<int, 3>());
    return true;
  }
} // namespace tissuefem
