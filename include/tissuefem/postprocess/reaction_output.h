#pragma once

#include <tissuefem/postprocess/interface.h>

#include <fstream>

namespace tissuefem::postprocess
{
  /**
   * reactions.csv: per step, the force each 'Output/Reactions/Boundary ids'
   * boundary applies to the body (force units; the sum of the unconstrained
   * nodal residual over the boundary's nodes); and in the summary file,
   * every 'Summary interval' steps, 't = T boundary B reaction = ...'.
   */
  template <int dim>
  class ReactionOutput : public Interface<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    explicit ReactionOutput(ParameterHandler &prm);

    /// Checks that every boundary id is on the mesh.
    void
    initialize(const Context<dim> &c) override;

    void
    open() override;

    std::vector<std::string>
    files() const override;

    void
    restore(const std::vector<std::string> &lines) override;

    void
    execute(const Step<dim> &step) override;

  private:
    std::vector<types::boundary_id> boundary_ids;
    std::ofstream                   file;
  };
} // namespace tissuefem::postprocess
