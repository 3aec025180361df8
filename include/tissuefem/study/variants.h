#pragma once

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace tissuefem::study
{
  using namespace dealii;

  /// One assignment 'Subsection/Name = value' given to a run with --set.
  struct Setting
  {
    std::string path;
    std::string value;

    /// "Subsection/Name=value", as --set takes it.
    std::string
    assignment() const
    {
      return path + "=" + value;
    }
  };

  /**
   * One choice along an axis: a label and the settings it makes. For an
   * axis over one parameter the label is the value; a named axis lists its
   * settings in braces.
   */
  struct AxisValue
  {
    std::string          label;
    std::vector<Setting> settings;
  };

  struct Axis
  {
    std::string            name;
    std::vector<AxisValue> values;
  };

  /// One run of a study: one value of every axis.
  struct Variant
  {
    unsigned int             index;
    std::string              label;
    std::vector<std::string> axis_labels;
    /// Per axis: 'Name=value' for one-parameter axes, else the label.
    std::vector<std::string> axis_pieces;
    std::vector<Setting>     settings;
  };

  /// Settings from "Path/Name = value; Path/Name = value" (';' separates,
  /// '&' does inside braces); a piece without '=' belongs to the value
  /// before it ("Output/Probes/Points = 0, 0; 1, 1"). Throws InputError
  /// naming @p parameter.
  std::vector<Setting>
  parse_settings(const std::string &text,
                 const char         separator,
                 const std::string &parameter);

  /**
   * Axes from the 'Study/Axes' syntax: axes separated by '|'; each is
   * 'Subsection/Name: v1; v2; ...' (one parameter) or 'name: label1
   * {P/N = v & P/N = v}; label2 {...}' (several parameters per value).
   */
  std::vector<Axis>
  parse_axes(const std::string &text, const std::string &parameter);

  /// Every combination of one value per axis; the first axis varies
  /// slowest. Settings of later axes come after (and override) earlier ones.
  std::vector<Variant>
  cartesian_product(const std::vector<Axis> &axes);

  /**
   * The variants of the 'Study/Axes' text: blocks separated by '||', each
   * the Cartesian product of its axes (parse_axes()), one after the other;
   * every block has the same axis names (e.g. an integrator axis with a
   * time step axis whose values suit that integrator). @p axes gets the
   * first block's axes. Variants are numbered from 1 across blocks.
   */
  std::vector<Variant>
  parse_variants(const std::string &text,
                 const std::string &parameter,
                 std::vector<Axis> &axes);
} // namespace tissuefem::study
