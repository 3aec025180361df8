#pragma once

#include <deal.II/base/parameter_handler.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/base/registry.h>

#include <memory>
#include <string>

namespace tissuefem::problems
{
  using namespace dealii;

  /// Facts about the invocation that parameters do not carry.
  struct RunContext
  {
    /// Directory of the parameter file; relative mesh paths start here.
    std::string parameter_directory;
    /// The parameter file, as given (for what a run shows of itself).
    std::string parameter_file;
    /// '--restart DIR': a checkpoint directory the run continues from
    /// (empty: start at t = 0).
    std::string restart_directory;
  };

  /**
   * What a parameter file asks tissuefem to do ('Problem' parameter). The
   * constructor reads the parameters; setup() builds everything and checks
   * all input without writing a file; run() computes and writes results.
   */
  class Interface
  {
  public:
    virtual ~Interface() = default;

    virtual void
    setup()
      = 0;

    virtual void
    run()
      = 0;
  };

  using ProblemRegistry
    = Registry<Interface, ParameterHandler &, const RunContext &>;

  /// Creates Problem<dim> for the 'Dimension' read from @p prm.
  template <template <int> class Problem>
  std::unique_ptr<Interface>
  create_for_dimension(ParameterHandler &prm, const RunContext &context)
  {
    switch (prm.get_integer("Dimension"))
      {
        case 1:
          return std::make_unique<Problem<1>>(prm, context);
        case 2:
          return std::make_unique<Problem<2>>(prm, context);
        default:
          return std::make_unique<Problem<3>>(prm, context);
      }
  }
} // namespace tissuefem::problems

/// Registers a problem template (on dim) at the end of its source file.
#define TISSUEFEM_REGISTER_PROBLEM(Problem, name, description)  \
  namespace                                                     \
  {                                                             \
    const bool tissuefem_registered_##Problem = [] {            \
      ::tissuefem::problems::ProblemRegistry::instance().add(   \
        name,                                                   \
        description,                                            \
        &Problem<3>::declare_parameters,                        \
        &::tissuefem::problems::create_for_dimension<Problem>); \
      return true;                                              \
    }();                                                        \
  }

/// Registers a problem that does not depend on the dimension (a class, not
/// a template: it computes nothing in space itself, e.g. the study, whose
/// variants are processes of their own) at the end of its source file.
#define TISSUEFEM_REGISTER_PROBLEM_WITHOUT_DIMENSION(Problem,       \
                                                     name,          \
                                                     description)   \
  namespace                                                         \
  {                                                                 \
    const bool tissuefem_registered_##Problem = [] {                \
      ::tissuefem::problems::ProblemRegistry::instance().add(       \
        name,                                                       \
        description,                                                \
        &Problem::declare_parameters,                               \
        [](::dealii::ParameterHandler              &prm,            \
           const ::tissuefem::problems::RunContext &context) {      \
          return std::unique_ptr<::tissuefem::problems::Interface>( \
            std::make_unique<Problem>(prm, context));               \
        });                                                         \
      return true;                                                  \
    }();                                                            \
  }
