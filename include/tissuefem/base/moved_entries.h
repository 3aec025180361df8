#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/patterns.h>

#include <string>

namespace tissuefem
{
  using namespace dealii;

  /**
   * Entries that moved to another place in the parameter tree (such as
   * 'Output/Probe points' to 'Output/Probes/Points' when the probes got a
   * subsection of their own), so that users' files keep working.
   * deal.II's ParameterHandler::declare_alias() only renames within one
   * subsection; a moved entry is instead declared at both places, and
   * after parsing a value given at the old place is copied to the new one.
   *
   * Paths are subsections and the entry's name joined by '/'.
   */
  namespace moved_entries
  {
    /**
     * Declares the entry at @p new_path (with @p default_value, @p pattern
     * and @p documentation) and at @p old_path, the latter documented as
     * moved. Call from a declare_parameters() at the top level of the
     * tree (any subsection entered is left again).
     */
    void
    declare(ParameterHandler            &prm,
            const std::string           &old_path,
            const std::string           &new_path,
            const std::string           &default_value,
            const Patterns::PatternBase &pattern,
            const std::string           &documentation);

    /**
     * Sets the entry at @p path (either place of a moved entry) to
     * @p value, for '--set' and a study's 'Settings': a moved entry gets it
     * at its new place, and its old place returns to the default, so that
     * the value overrides whatever the file gave at either place.
     */
    void
    set(ParameterHandler  &prm,
        const std::string &path,
        const std::string &value);

    /**
     * After parsing: every moved entry whose old place holds a value other
     * than the default gets it at its new place, with a one-line notice on
     * stderr (process 0, once per entry). Throws InputError if both places
     * hold different values other than the default.
     */
    void
    apply(ParameterHandler &prm);
  } // namespace moved_entries
} // namespace tissuefem
