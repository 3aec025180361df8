#include <tissuefem/study/picker.h>

#include <algorithm>
#include <iomanip>
#include <numeric>
#include <sstream>

namespace tissuefem::study
{
  void
  PickerParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Model choice");
    prm.declare_entry("Tolerance",
                      "0",
                      Patterns::Double(0),
                      "Largest acceptable error in the study's quantity "
                      "(its units); 0 leaves the choice out.");
    prm.declare_entry("Budget per step",
                      "0",
                      Patterns::List(Patterns::Double(0)),
                      "Wall-clock time one step may take (s), compared with "
                      "each variant's 95th percentile of step wall times: "
                      "1/30 for a visual loop, 1/500 for haptics. Several "
                      "budgets give one choice each. 0: no budget.");
    prm.declare_entry("Run choice",
                      "true",
                      Patterns::Bool(),
                      "Run the scene with the chosen variant's settings "
                      "(into '<Study/Directory>/choice-K' for the K-th "
                      "budget).");
    prm.leave_subsection();
  }


  void
  PickerParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Model choice");
    tolerance  = prm.get_double("Tolerance");
    budgets.clear();
    for (const auto &b : Utilities::split_string_list(prm.get("Budget per step")))
      budgets.push_back(Utilities::string_to_double(b));
    if (budgets.empty())
      budgets.push_back(0);
    run_choice = prm.get_bool("Run choice");
    prm.leave_subsection();
  }


  Choice
  pick(const std::vector<Row> &rows,
       const double            tolerance,
       const double            budget,
       const std::string      &quantity)
  {
    std::vector<unsigned int> order(rows.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](unsigned a, unsigned b) {
      return rows[a].cost() < rows[b].cost();
    });
    std::ostringstream why;
    why << std::setprecision(3);
    const auto facts = [&](const Row &r) {
      std::ostringstream f;
      f << std::setprecision(3) << "#" << r.variant.index << " ("
        << r.variant.label << "): error " << r.error << ", step wall time "
        << r.get("step p95") << " s (95th percentile), " << r.cost()
        << " s of wall time per simulated time unit";
      return f.str();
    };
    Choice choice;
    std::vector<std::string> passed_over;
    for (const unsigned int i : order)
      {
        const Row &r = rows[i];
        if (!r.finished)
          continue;
        const bool accurate = r.error <= tolerance;
        const bool in_time
          = budget == 0 || r.get("step p95") <= budget;
        if (accurate && in_time)
          {
            choice.row = i;
            break;
          }
        passed_over.push_back(
          facts(r) + (accurate ? "; too slow" :
                      in_time  ? "; not accurate enough" :
                                 "; too slow and not accurate enough"));
      }
    why << "Model choice for " << quantity << " at most " << tolerance
        << " and "
        << (budget > 0 ? "at most " + std::to_string(budget) + " s" :
                         std::string("any"))
        << " of wall time per step: ";
    if (choice.row)
      why << "chose " << facts(rows[*choice.row])
          << ", the cheapest per simulated time of the variants that meet "
             "both.";
    else
      why << "no variant meets both.";
    if (!passed_over.empty())
      {
        why << " Cheaper variants passed over:";
        for (const auto &s : passed_over)
          why << "\n  " << s;
      }
    choice.explanation = why.str();
    return choice;
  }
} // namespace tissuefem::study
