#include <tissuefem/study/picker.h>

#include <algorithm>
#include <cmath>
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
                      Patterns::List(Patterns::Double(0)),
                      "Largest acceptable error in the study's quantity "
                      "(its units); several give one choice each (with each "
                      "budget); 0 leaves the choice out.");
    prm.declare_entry("Budget per step",
                      "0",
                      Patterns::List(Patterns::Double(0)),
                      "The frame of a real-time loop (s): 1/30 for a visual "
                      "loop, 1/500 for haptics. A variant meets it if its "
                      "steps are at most a frame long (simulated time) and "
                      "the steps of one frame, at the 95th percentile of its "
                      "step wall times, take at most a frame of wall time. "
                      "Several budgets give one choice each. 0: no budget.");
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
    tolerances.clear();
    for (const auto &t : Utilities::split_string_list(prm.get("Tolerance")))
      tolerances.push_back(Utilities::string_to_double(t));
    budgets.clear();
    for (const auto &b :
         Utilities::split_string_list(prm.get("Budget per step")))
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
    // A frame: the budget B in wall time must advance the simulation by B
    // (real time at that frame rate), with at least one state per frame.
    const auto frame_steps = [&](const Row &r) {
      const double dt = r.mean_step();
      return dt > 0 ? std::max(1., std::ceil(budget / dt * (1 - 1e-9))) : 1.;
    };
    const auto facts = [&](const Row &r) {
      std::ostringstream f;
      f << std::setprecision(3) << "#" << r.variant.index << " ("
        << r.variant.label << "): error " << r.error << ", step "
        << r.mean_step() << " (time units, mean), " << r.get("step p95")
        << " s wall per step (95th percentile)";
      if (budget > 0)
        f << ", " << frame_steps(r) * r.get("step p95") << " s per frame";
      f << ", " << r.cost() << " s wall per simulated time unit";
      return f.str();
    };
    Choice                   choice;
    std::vector<std::string> passed_over;
    for (const unsigned int i : order)
      {
        const Row &r = rows[i];
        if (!r.finished)
          continue;
        const bool accurate = r.error <= tolerance;
        const bool coarse   = budget > 0 && r.mean_step() > budget * (1 + 1e-9);
        const bool slow
          = budget > 0 && frame_steps(r) * r.get("step p95") > budget;
        if (accurate && !coarse && !slow)
          {
            choice.row = i;
            break;
          }
        std::string missed;
        if (!accurate)
          missed += "; not accurate enough";
        if (coarse)
          missed += "; steps longer than a frame";
        else if (slow)
          missed += "; slower than real time at this frame";
        passed_over.push_back(facts(r) + missed);
      }
    why << "Model choice for " << quantity << " at most " << tolerance;
    if (budget > 0)
      why << " in real time at frames of " << budget
          << " s (each frame advances the simulation by the frame's duration "
             "in at most that much wall time, taking steps of at most a "
             "frame)";
    why << ": ";
    if (choice.row)
      why << "chose " << facts(rows[*choice.row])
          << ", the cheapest per simulated time of the variants that meet "
             "both.";
    else
      why << "no variant meets both.";
    if (!passed_over.empty())
      {
        why << " Cheaper variants passed over:";
        for (const auto &line : passed_over)
          why << "\n  " << line;
      }
    choice.explanation = why.str();
    return choice;
  }
} // namespace tissuefem::study
