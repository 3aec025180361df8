#pragma once

#include <tissuefem/postprocess/interface.h>

#include <fstream>

namespace tissuefem::postprocess
{
  /**
   * contact.csv, in scenes with obstacles ('Contact'): per step and
   * obstacle, the resultant force of the obstacle on the tissue (force
   * units), the largest penetration (length units) and the reference area
   * in contact (length^(dim-1) units); and in the summary file, every
   * 'Summary interval' steps, 't = T obstacle NAME force = ...' and
   * '... penetration = ...'.
   */
  template <int dim>
  class ContactOutput : public Interface<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);
    explicit ContactOutput(ParameterHandler &prm);
    void
    open() override;
    std::vector<std::string>
    files() const override;
    void
    restore(const std::vector<std::string> &lines) override;
    void
    execute(const Step<dim> &step) override;

  private:
    std::ofstream file;
  };
} // namespace tissuefem::postprocess
