#include <tissuefem/output/output_files.h>
#include <tissuefem/postprocess/reaction_output.h>

#include <algorithm>
#include <sstream>

#include <tissuefem/base/moved_entries.h>

namespace tissuefem::postprocess
{
  template <int dim>
  void
  ReactionOutput<dim>::declare_parameters(ParameterHandler &prm)
  {
    moved_entries::declare(
      prm,
      "Output/Reaction boundary ids",
      "Output/Reactions/Boundary ids",
      "",
      Patterns::List(Patterns::Integer(0, 254)),
      "Boundary ids whose reaction force goes to reactions.csv every step: "
      "the force the prescribed boundary applies to the body (force units), "
      "i.e. the sum of the unconstrained nodal residual over the boundary's "
      "nodes. A tool holding the boundary feels the opposite force.");
  }


  template <int dim>
  ReactionOutput<dim>::ReactionOutput(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.enter_subsection("Reactions");
    for (const auto &id : Utilities::split_string_list(prm.get("Boundary ids")))
      boundary_ids.push_back(Utilities::string_to_int(id));
    prm.leave_subsection();
    prm.leave_subsection();
  }


  template <int dim>
  void
  ReactionOutput<dim>::initialize(const Context<dim> &c)
  {
    Interface<dim>::initialize(c);
    const auto present = c.scene.triangulation.get_boundary_ids();
    for (const auto id : boundary_ids)
      require(std::find(present.begin(), present.end(), id) != present.end(),
              "Output/Reactions/Boundary ids",
              "boundary id " + std::to_string(id)
                + " is on no boundary face of the mesh");
  }


  template <int dim>
  std::vector<std::string>
  ReactionOutput<dim>::files() const
  {
    if (boundary_ids.empty())
      return {};
    return {this->context->directory + "/reactions.csv"};
  }


  template <int dim>
  void
  ReactionOutput<dim>::open()
  {
    if (boundary_ids.empty() || !parallel_tools::is_root())
      return;
    static const char *coordinates[] = {"X", "Y", "Z"};
    output::create_file(file, files()[0]);
    file << "time,boundary";
    for (unsigned int d = 0; d < dim; ++d)
      file << ",F" << coordinates[d];
    file << '\n' << std::flush;
  }


  template <int dim>
  void
  ReactionOutput<dim>::restore(const std::vector<std::string> &)
  {
    if (!boundary_ids.empty() && parallel_tools::is_root())
      output::append_to_file(file, files()[0]);
  }


  template <int dim>
  void
  ReactionOutput<dim>::execute(const Step<dim> &step)
  {
    if (boundary_ids.empty())
      return;
    const auto &state     = step.state;
    const auto  reactions = this->context->scene.solid->reaction_forces(
      state.u, state.a, state.time, state.damping, boundary_ids);
    if (!parallel_tools::is_root())
      return;
    const bool summarize = this->context->summary.due(step.number);
    for (unsigned int b = 0; b < boundary_ids.size(); ++b)
      {
        file << state.time << ',' << int(boundary_ids[b]);
        for (unsigned int c = 0; c < dim; ++c)
          file << ',' << reactions[b * dim + c];
        file << '\n';
        if (summarize)
          this->context->summary.line(output::vector_line(
            state.time,
            "boundary " + std::to_string(int(boundary_ids[b])) + " reaction",
            &reactions[b * dim],
            dim));
      }
    file << std::flush;
  }

  template class ReactionOutput<1>;
  template class ReactionOutput<2>;
  template class ReactionOutput<3>;

  TISSUEFEM_REGISTER_POSTPROCESSOR(ReactionOutput,
                                   "reactions",
                                   "reactions.csv: the force through each "
                                   "'Output/Reactions/Boundary ids' boundary.")
} // namespace tissuefem::postprocess
