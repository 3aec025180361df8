#include <tissuefem/base/input_error.h>
#include <tissuefem/base/nan_aware.h>
#include <tissuefem/base/parameter_tools.h>
#include <tissuefem/output/run_record.h>
#include <tissuefem/study/quantity.h>

#include <cmath>
#include <fstream>
#include <sstream>

namespace tissuefem::study
{
  namespace
  {
    const std::string manufactured_quantities
      = "L2 error|H1 error|relative L2 error|relative H1 error|max L2 "
        "error|L2L2 error";
  }


  void
  QuantityParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry(
      "Quantity",
      "probe final",
      Patterns::Selection(manufactured_quantities
                          + "|probe final|probe history|stored energy"),
      "What the error is measured in. With a manufactured solution "
      "(Reference = manufactured): 'L2 error' ||u_h - u||_L2 and 'H1 error' "
      "||Grad(u_h - u)||_L2 at the end time, their relative forms, 'max L2 "
      "error' (largest over the steps) and 'L2L2 error' (in space and time). "
      "Otherwise: 'probe final' |u_h(p, T) - u_ref(p, T)| (length units) at "
      "the probe 'Probe' of the scene's 'Output/Probes/Points'; 'probe "
      "history' the largest such difference over the reference's output "
      "times (the variant's probe interpolated linearly in time); 'stored "
      "energy' |E - E_ref| at the end (energy units).");
    prm.declare_entry("Probe",
                      "0",
                      Patterns::Integer(0),
                      "Index of the probe point for probe quantities.");
    prm.declare_entry("Component",
                      "all",
                      Patterns::Selection("all|x|y|z"),
                      "Probe quantities: the displacement component compared "
                      "('all': the Euclidean distance of the vectors).");
    prm.declare_entry("Reference",
                      "reference run",
                      Patterns::Selection("manufactured|value|reference run"),
                      "What errors are measured against: the manufactured "
                      "solution (the scene must enable 'Manufactured "
                      "solution'), a closed-form 'Reference value', or a "
                      "'reference run' of the scene with 'Reference "
                      "settings' (finer than every variant).");
    prm.declare_entry("Reference value",
                      "",
                      Patterns::Anything(),
                      "The exact value: dim displacement components for "
                      "'probe final' (length units; one with 'Component'), "
                      "one number for 'stored energy' (energy units).");
    prm.declare_entry("Reference settings",
                      "",
                      Patterns::Anything(),
                      "'Subsection/Name = value; ...' for the reference run, "
                      "on top of 'Settings'.");
    prm.declare_entry("Relative",
                      "false",
                      Patterns::Bool(),
                      "Divide the error by the size of the reference value "
                      "(a dimensionless error).");
  }


  void
  QuantityParameters::parse_parameters(ParameterHandler &prm)
  {
    quantity            = prm.get("Quantity");
    probe               = prm.get_integer("Probe");
    const std::string c = prm.get("Component");
    component           = c == "all" ? -1 : c == "x" ? 0 : c == "y" ? 1 : 2;
    reference           = prm.get("Reference");
    reference_settings  = prm.get("Reference settings");
    relative            = prm.get_bool("Relative");
    reference_value.clear();
    for (const std::string &x : split_and_trim(prm.get("Reference value"), ','))
      if (!x.empty())
        {
          try
            {
              reference_value.push_back(std::stod(x));
            }
          catch (const std::exception &)
            {
              throw InputError("Parameter 'Study/Reference value': '" + x
                               + "' is not a number");
            }
        }
    const bool manufactured_quantity
      = ("|" + manufactured_quantities + "|").find("|" + quantity + "|")
        != std::string::npos;
    require(manufactured_quantity == (reference == "manufactured"),
            "Study/Quantity",
            "'" + quantity + "' "
              + (manufactured_quantity ? "needs 'Reference = manufactured'"
                                       : "cannot be used with 'Reference = "
                                         "manufactured'"));
    require(reference != "value" || !reference_value.empty(),
            "Study/Reference value",
            "is needed with 'Reference = value'");
    require(reference != "value" || quantity != "probe history",
            "Study/Quantity",
            "'probe history' needs a reference run, not a value");
    require(reference != "reference run" || !reference_settings.empty(),
            "Study/Reference settings",
            "is needed with 'Reference = reference run' (the settings that "
            "make the scene finer than every variant)");
  }


  std::string
  QuantityParameters::describe() const
  {
    std::string unit;
    if (quantity == "probe final" || quantity == "probe history")
      unit = "length units";
    else if (quantity == "stored energy")
      unit = "energy units";
    else if (quantity.find("relative") != std::string::npos)
      unit = "relative";
    else if (quantity.find("H1") != std::string::npos)
      unit = "||Grad(u_h - u)||_L2";
    else
      unit = "length units";
    const std::string against = reference == "manufactured"
                                  ? "the manufactured solution"
                                : reference == "value" ? "the reference value"
                                                       : "the reference run";
    return quantity
           + (quantity.rfind("probe", 0) == 0
                ? " " + std::to_string(probe)
                    + (component < 0 ? ""
                                     : std::string(" u_") + "xyz"[component])
                : "")
           + (quantity.find("error") == std::string::npos ? " error" : "")
           + " against " + against + " (" + (relative ? "relative" : unit)
           + ")";
  }


  ProbeHistory
  read_probe_history(const std::string &directory,
                     const unsigned int probe,
                     const int          component)
  {
    const std::string file = directory + "/probes.csv";
    std::ifstream     in(file);
    if (!in)
      throw InputError("'" + file
                       + "' cannot be read (the scene needs "
                         "'Output/Probes/Points')");
    std::string header;
    std::getline(in, header);
    const unsigned int n_columns = split_and_trim(header, ',').size();
    // time, probe, X..., u...: as many displacement as coordinate columns.
    const unsigned int dim = (n_columns - 2) / 2;
    ProbeHistory       history;
    for (std::string line; std::getline(in, line);)
      {
        const auto fields = split_and_trim(line, ',');
        if (fields.size() != n_columns)
          throw InputError("'" + file + "': malformed line '" + line + "'");
        if (std::stoul(fields[1]) != probe)
          continue;
        std::vector<double> u;
        for (unsigned int d = 0; d < dim; ++d)
          if (component < 0 || static_cast<int>(d) == component)
            u.push_back(std::stod(fields[2 + dim + d]));
        if (u.empty())
          throw InputError("Parameter 'Study/Component': '" + file
                           + "' has no such displacement component");
        history[std::stod(fields[0])] = u;
      }
    if (history.empty())
      throw InputError("'" + file + "' has no rows for probe "
                       + std::to_string(probe));
    return history;
  }


  namespace
  {
    /// |a - b| in the Euclidean norm.
    double
    distance(const std::vector<double> &a, const std::vector<double> &b)
    {
      double s = 0;
      for (unsigned int i = 0; i < std::min(a.size(), b.size()); ++i)
        s += (a[i] - b[i]) * (a[i] - b[i]);
      return std::sqrt(s);
    }


    double
    norm(const std::vector<double> &a)
    {
      return distance(a, std::vector<double>(a.size(), 0.));
    }


    /// The history at time t, linear between the two nearest times.
    std::vector<double>
    interpolate(const ProbeHistory &h, const double t)
    {
      auto upper = h.lower_bound(t);
      if (upper == h.end())
        return std::prev(h.end())->second;
      if (upper == h.begin() || upper->first == t)
        return upper->second;
      const auto   lower = std::prev(upper);
      const double w     = (t - lower->first) / (upper->first - lower->first);
      std::vector<double> u(lower->second.size());
      for (unsigned int i = 0; i < u.size(); ++i)
        u[i] = (1 - w) * lower->second[i] + w * upper->second[i];
      return u;
    }
  } // namespace


  double
  quantity_error(const QuantityParameters            &p,
                 const std::string                   &directory,
                 const std::map<std::string, double> &record,
                 const std::string                   &reference_directory)
  {
    if (p.reference == "manufactured")
      {
        const auto it = record.find(p.quantity);
        require(it != record.end(),
                "Study/Quantity",
                "the run in '" + directory + "' reports no '" + p.quantity
                  + "' (is 'Manufactured solution/Enabled' true?)");
        return it->second;
      }
    double error = 0, size = 0;
    if (p.quantity == "stored energy")
      {
        const double reference
          = p.reference == "value"
              ? p.reference_value[0]
              : output::RunRecord::read(reference_directory + "/run.txt")
                  .at("stored energy");
        error = std::abs(record.at("stored energy") - reference);
        size  = std::abs(reference);
      }
    else
      {
        const ProbeHistory run
          = read_probe_history(directory, p.probe, p.component);
        if (p.reference == "value")
          {
            error = distance(run.rbegin()->second, p.reference_value);
            size  = norm(p.reference_value);
          }
        else
          {
            const ProbeHistory reference
              = read_probe_history(reference_directory, p.probe, p.component);
            if (p.quantity == "probe final")
              {
                error
                  = distance(run.rbegin()->second, reference.rbegin()->second);
                size = norm(reference.rbegin()->second);
              }
            else
              for (const auto &[t, u] : reference)
                if (t <= run.rbegin()->first * (1 + 1e-12))
                  {
                    error = max_keeping_nan(error,
                                            distance(interpolate(run, t), u));
                    size  = std::max(size, norm(u));
                  }
          }
      }
    return p.relative ? error / size : error;
  }
} // namespace tissuefem::study
