#include <deal.II/base/utilities.h>
#include <deal.II/lac/vector.h>

#include <tissuefem/base/cerr_capture.h>
#include <tissuefem/base/input_error.h>
#include <tissuefem/base/parameter_tools.h>

#include <cctype>

#include <cmath>
#include <iostream>
#include <map>
#include <sstream>

namespace tissuefem
{
  std::vector<std::string>
  split_and_trim(const std::string &text, const char separator)
  {
    std::vector<std::string> pieces;
    std::string              current;
    for (const char c : text)
      if (c == separator)
        {
          pieces.push_back(Utilities::trim(current));
          current.clear();
        }
      else
        current += c;
    pieces.push_back(Utilities::trim(current));
    return pieces;
  }


  std::vector<std::string>
  split_entries(const std::string &text)
  {
    std::vector<std::string> entries;
    std::string              current;
    for (std::size_t i = 0; i < text.size(); ++i)
      {
        if (text[i] == '|')
          {
            const bool doubled = (i + 1 < text.size() && text[i + 1] == '|');
            if (doubled)
              {
                current += "||";
                ++i;
                continue;
              }
            entries.push_back(Utilities::trim(current));
            current.clear();
          }
        else
          current += text[i];
      }
    if (!Utilities::trim(current).empty() || !entries.empty())
      entries.push_back(Utilities::trim(current));
    return entries;
  }


  types::boundary_id
  parse_boundary_id(const std::string &text, const std::string &parameter)
  {
    int id = -1;
    try
      {
        std::size_t used = 0;
        id               = std::stoi(text, &used);
        if (used != text.size())
          id = -1;
      }
    catch (...)
      {
      }
    require(id >= 0 && id < 255,
            parameter,
            "'" + text + "' is not a boundary id 0..254");
    return id;
  }


  std::vector<std::pair<types::boundary_id, std::string>>
  parse_id_entries(const std::string &text, const std::string &parameter)
  {
    std::vector<std::pair<types::boundary_id, std::string>> result;
    for (const auto &entry : split_entries(text))
      {
        const auto colon = entry.find(':');
        require(colon != std::string::npos,
                parameter,
                "entry '" + entry + "' does not start with 'id:'");
        result.emplace_back(
          parse_boundary_id(Utilities::trim(entry.substr(0, colon)), parameter),
          Utilities::trim(entry.substr(colon + 1)));
      }
    return result;
  }


  bool
  names_variable(const std::string &expression, const std::string &name)
  {
    std::string identifier;
    for (const char c : expression + ' ')
      if (std::isalnum(static_cast<unsigned char>(c)) || c == '_')
        identifier += c;
      else
        {
          if (identifier == name)
            return true;
          identifier.clear();
        }
    return false;
  }


  std::string
  expression_variables(const unsigned int dim)
  {
    static const char *names[] = {"x", "y", "z"};
    std::string        result;
    for (unsigned int d = 0; d < dim; ++d)
      result += std::string(names[d]) + ",";
    return result + "t";
  }


  std::vector<double>
  parse_numbers(const std::string &text, const std::string &what)
  {
    std::vector<double> values;
    for (const auto &item : Utilities::split_string_list(text, ','))
      {
        std::size_t end   = 0;
        double      value = 0;
        try
          {
            value = std::stod(item, &end);
          }
        catch (...)
          {
            end = 0;
          }
        if (end != item.size() || !std::isfinite(value))
          throw InputError(what + ": '" + item + "' is not a finite number");
        values.push_back(value);
      }
    return values;
  }


  template <int dim>
  std::unique_ptr<FunctionParser<dim>>
  make_function(const std::string &expressions,
                const unsigned int n_components,
                const std::string &parameter)
  {
    std::vector<std::string> pieces = split_and_trim(expressions, ';');
    if (pieces.size() == 1 && n_components > 1)
      pieces.resize(n_components, pieces[0]);
    require(pieces.size() == n_components,
            parameter,
            "expected " + std::to_string(n_components)
              + " expressions separated by ';', got "
              + std::to_string(pieces.size()) + " in '" + expressions + "'");
    for (const auto &piece : pieces)
      require(!piece.empty(),
              parameter,
              "empty expression in '" + expressions + "'");

    auto function = std::make_unique<FunctionParser<dim>>(n_components);
    const std::map<std::string, double> constants = {{"pi", M_PI}};
    // deal.II's muparser wrapper prints its own multi-line report of a
    // syntax error to std::cerr; silence it, since the error is reported
    // (on one line, naming the parameter) by the exception below.
    const CerrCapture muted;
    try
      {
        function->initialize(expression_variables(dim),
                             pieces,
                             constants,
                             /*time_dependent=*/true);
        // muparser may parse lazily; evaluating once makes every syntax
        // error surface here, where we can still name the parameter.
        Vector<double> values(n_components);
        function->vector_value(Point<dim>(), values);
      }
    catch (const ExceptionBase &e)
      {
        throw InputError("Parameter '" + parameter
                         + "': cannot parse expression '" + expressions
                         + "': " + one_line_message(e));
      }
    return function;
  }


  template <int dim>
  Point<dim>
  parse_point(const std::string &text, const std::string &parameter)
  {
    const std::vector<std::string> pieces = split_and_trim(text, ',');
    require(pieces.size() == dim,
            parameter,
            "expected a point with " + std::to_string(dim)
              + " coordinates separated by ',', got '" + text + "'");
    Point<dim> p;
    for (unsigned int d = 0; d < dim; ++d)
      {
        std::size_t used = 0;
        try
          {
            p[d] = std::stod(pieces[d], &used);
          }
        catch (...)
          {
            used = 0;
          }
        require(used == pieces[d].size() && used > 0 && std::isfinite(p[d]),
                parameter,
                "'" + pieces[d] + "' is not a number (in '" + text + "')");
      }
    return p;
  }


  std::string
  leading_entries(const std::string &text,
                  const char         separator,
                  const unsigned int n)
  {
    std::vector<std::string> pieces = split_and_trim(text, separator);
    if (pieces.size() > n)
      pieces.resize(n);
    std::string result;
    for (const auto &piece : pieces)
      result += (result.empty() ? "" : std::string(1, separator) + " ") + piece;
    return result;
  }


  template <int dim>
  Point<dim>
  parse_leading_point(const std::string &text, const std::string &parameter)
  {
    require(split_and_trim(text, ',').size() >= dim,
            parameter,
            "needs at least " + std::to_string(dim) + " coordinates, got '"
              + text + "'");
    return parse_point<dim>(leading_entries(text, ',', dim), parameter);
  }


  template <int dim>
  std::vector<Point<dim>>
  parse_points(const std::string &text, const std::string &parameter)
  {
    std::vector<Point<dim>> points;
    if (Utilities::trim(text).empty())
      return points;
    for (const auto &piece : split_and_trim(text, ';'))
      points.push_back(parse_point<dim>(piece, parameter));
    return points;
  }


  std::string
  squeeze_whitespace(const std::string &text)
  {
    std::string result;
    bool        in_space = false;
    for (const char c : text)
      {
        if (std::isspace(static_cast<unsigned char>(c)))
          in_space = !result.empty();
        else
          {
            if (in_space)
              result += ' ';
            result += c;
            in_space = false;
          }
      }
    return result;
  }


  std::string
  one_line_message(const ExceptionBase &exception)
  {
    std::ostringstream info;
    exception.print_info(info);
    std::string message = squeeze_whitespace(info.str());
    return message.empty() ? squeeze_whitespace(exception.get_exc_name())
                           : message;
  }


#define TISSUEFEM_INSTANTIATE(dim)                                                \
  template std::unique_ptr<FunctionParser<dim>> make_function<dim>(               \
    const std::string &, const unsigned int, const std::string &);                \
  template Point<dim>              parse_point<dim>(const std::string &,          \
                                       const std::string &);         \
  template Point<dim>              parse_leading_point<dim>(const std::string &,  \
                                               const std::string &); \
  template std::vector<Point<dim>> parse_points<dim>(const std::string &,         \
                                                     const std::string &);
  TISSUEFEM_INSTANTIATE(1)
  TISSUEFEM_INSTANTIATE(2)
  TISSUEFEM_INSTANTIATE(3)
#undef TISSUEFEM_INSTANTIATE
} // namespace tissuefem
