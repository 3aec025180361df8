#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/study/variants.h>

namespace tissuefem::study
{
  std::vector<Setting>
  parse_settings(const std::string &text,
                 const char         separator,
                 const std::string &parameter)
  {
    std::vector<Setting> settings;
    for (const std::string &item : split_and_trim(text, separator))
      {
        if (item.empty())
          continue;
        const auto equals = item.find('=');
        // A piece without '=' continues the previous value: values such as
        // probe points or per-component expressions contain separators.
        if (equals == std::string::npos && !settings.empty())
          {
            settings.back().value += std::string(1, separator) + " " + item;
            continue;
          }
        require(equals != std::string::npos && equals > 0,
                parameter,
                "'" + item + "' is not 'Subsection/Name = value'");
        settings.push_back({Utilities::trim(item.substr(0, equals)),
                            Utilities::trim(item.substr(equals + 1))});
      }
    return settings;
  }


  std::vector<Axis>
  parse_axes(const std::string &text, const std::string &parameter)
  {
    std::vector<Axis> axes;
    for (const std::string &axis_text : split_and_trim(text, '|'))
      {
        if (axis_text.empty())
          continue;
        const auto colon = axis_text.find(':');
        require(colon != std::string::npos && colon > 0,
                parameter,
                "axis '" + axis_text + "' is not 'name: value; value; ...'");
        Axis axis;
        axis.name = Utilities::trim(axis_text.substr(0, colon));
        for (const std::string &value :
             split_and_trim(axis_text.substr(colon + 1), ';'))
          {
            require(!value.empty(),
                    parameter,
                    "axis '" + axis.name + "' has an empty value");
            const auto open = value.find('{');
            if (open == std::string::npos)
              {
                // A value of the parameter the axis is named after.
                require(axis.name.find('/') != std::string::npos,
                        parameter,
                        "axis '" + axis.name
                          + "' is no 'Subsection/Name', so its values need "
                            "'label {Subsection/Name = value & ...}'");
                axis.values.push_back({value, {{axis.name, value}}});
                continue;
              }
            const auto close = value.rfind('}');
            require(close != std::string::npos && close > open
                      && close + 1 == value.size(),
                    parameter,
                    "value '" + value + "' of axis '" + axis.name
                      + "' has unbalanced braces");
            AxisValue v;
            v.label = Utilities::trim(value.substr(0, open));
            v.settings
              = parse_settings(value.substr(open + 1, close - open - 1),
                               '&',
                               parameter);
            require(!v.label.empty(),
                    parameter,
                    "value '" + value + "' of axis '" + axis.name
                      + "' needs a label before '{'");
            axis.values.push_back(v);
          }
        require(!axis.values.empty(),
                parameter,
                "axis '" + axis.name + "' has no values");
        axes.push_back(axis);
      }
    return axes;
  }


  std::vector<Variant>
  cartesian_product(const std::vector<Axis> &axes)
  {
    std::vector<Variant> variants(1);
    for (const Axis &axis : axes)
      {
        std::vector<Variant> next;
        for (const Variant &v : variants)
          for (const AxisValue &value : axis.values)
            {
              Variant w = v;
              w.axis_labels.push_back(value.label);
              w.settings.insert(w.settings.end(),
                                value.settings.begin(),
                                value.settings.end());
              next.push_back(w);
            }
        variants = next;
      }
    for (unsigned int i = 0; i < variants.size(); ++i)
      {
        variants[i].index = i + 1;
        for (unsigned int a = 0; a < axes.size(); ++a)
          {
            const std::string &name  = axes[a].name;
            const auto         slash = name.rfind('/');
            // One-parameter axes are labelled 'Name=value', named ones by
            // their value label alone.
            const std::string piece
              = slash == std::string::npos
                  ? variants[i].axis_labels[a]
                  : name.substr(slash + 1) + "=" + variants[i].axis_labels[a];
            variants[i].axis_pieces.push_back(piece);
            variants[i].label += (a ? ", " : "") + piece;
          }
      }
    return variants;
  }


  std::vector<Variant>
  parse_variants(const std::string &text,
                 const std::string &parameter,
                 std::vector<Axis> &axes)
  {
    std::vector<Variant> variants;
    axes.clear();
    std::string rest = text;
    while (true)
      {
        const auto        split      = rest.find("||");
        const std::string block      = rest.substr(0, split);
        const auto        block_axes = parse_axes(block, parameter);
        if (axes.empty())
          axes = block_axes;
        require(block_axes.size() == axes.size(),
                parameter,
                "every block (separated by '||') needs the same axes");
        for (unsigned int a = 0; a < axes.size(); ++a)
          require(block_axes[a].name == axes[a].name,
                  parameter,
                  "axis '" + block_axes[a].name + "' of a later block is not '"
                    + axes[a].name + "' (blocks need the same axes, in order)");
        for (Variant v : cartesian_product(block_axes))
          {
            v.index = variants.size() + 1;
            variants.push_back(v);
          }
        if (split == std::string::npos)
          break;
        rest = rest.substr(split + 2);
      }
    return variants;
  }
} // namespace tissuefem::study
