
#include <tissuefem/base/input_error.h>
#include <tissuefem/contact/penalty_contact.h>
#include <tissuefem/geometry/distribution.h>

namespace tissuefem::contact
{
  template <int dim>
  void
  PenaltyContact<dim>::declare_parameters(ParameterHandler &prm)
  {
    Obstacle<dim>::declare_parameters(prm);
    prm.enter_subsection("Contact");
    prm.declare_entry(
      "Penalty factor",
      "100",
      Patterns::Double(0),
      "Dimensionless: the penalty stiffness per unit area is this times the "
      "largest Young's modulus of the materials over the diameter of the "
      "contact point's cell (stress / length units). The penetration under "
      "a contact pressure p is then p h / (factor E): at 100, a hundredth "
      "of the strain p / E the pressure causes, times the cell size. "
      "Larger is closer to no penetration and stiffer for Newton and for "
      "explicit steps. Must be > 0. With the augmented Lagrangian it sets "
      "only how fast the multiplier updates converge.");
    prm.declare_entry(
      "Method",
      "penalty",
      Patterns::Selection("penalty|augmented Lagrangian"),
      "How contact is enforced. 'penalty': a pressure k times the "
      "penetration, which leaves a penetration of p / k. 'augmented "
      "Lagrangian': a multiplier per contact point, updated after each "
      "converged solve of a step (Uzawa) until every gap is within 'Gap "
      "tolerance'; each update costs a Newton solve (usually 1-3 "
      "iterations). Needs an implicit one-step integrator (backward Euler "
      "or quasistatic).");
    prm.declare_entry(
      "Gap tolerance",
      "0",
      Patterns::Double(0),
      "Augmented Lagrangian: the largest gap accepted at a contact point "
      "(length units): its penetration, or its distance from the obstacle "
      "where it is pressed. With friction, also the largest change of a "
      "stuck point's slip between the last two solves of a step. 0 takes "
      "1e-4 times the body's diameter. Keep it above 'Newton solver/"
      "Displacement tolerance' times the diameter: Newton stops each solve "
      "within that, and smaller gaps and slips are then round-off that the "
      "updates cannot settle (a block on a turntable with friction: 1e-9 "
      "on a body of size 1 failed every step, 1e-8 ran).");
    prm.declare_entry(
      "Maximum multiplier updates",
      "50",
      Patterns::Integer(1, 10000),
      "Augmented Lagrangian: the updates a step may take to bring every "
      "gap within 'Gap tolerance'; beyond, the step fails (and may be "
      "retried shorter).");
    prm.declare_entry(
      "Start penetration tolerance",
      "0",
      Patterns::Double(0),
      "How deep an obstacle may start inside the tissue (length units): a "
      "deeper start is refused before the run writes anything (the first "
      "step would throw the tissue off with the penalty's whole force). 0 "
      "takes 1e-3 times the body's diameter.");
    prm.declare_entry(
      "Tangential penalty ratio",
      "0.01",
      Patterns::Double(1e-12, 1),
      "Friction (an obstacle's 'Friction coefficient' > 0): the tangential "
      "penalty over the normal one (dimensionless, in (0, 1]). With the "
      "augmented Lagrangian a stuck point sticks exactly once the "
      "multiplier updates settle, whatever the ratio; a stiff tangential "
      "penalty leaves Newton a narrow band between sticking and sliding, "
      "where it crawls, and a soft one takes more updates. With the "
      "penalty a stuck point may slip by up to its friction bound over "
      "the tangential penalty, mu / ratio times its penetration.");
    prm.leave_subsection();
  }


  template <int dim>
  PenaltyContact<dim>::PenaltyContact(
    ParameterHandler                 &prm,
    const solid::Discretization<dim> &discretization,
    std::vector<Obstacle<dim>>        obstacles,
    const double                      modulus)
      : discretization(discretization)
      , boundary(discretization)
      , obstacle_list(std::move(obstacles))
      , modulus(modulus)
  {
    prm.enter_subsection("Contact");
    factor          = prm.get_double("Penalty factor");
    augmented       = prm.get("Method") == "augmented Lagrangian";
    tolerance       = prm.get_double("Gap tolerance");
    max_updates     = prm.get_integer("Maximum multiplier updates");
    tangential      = prm.get_double("Tangential penalty ratio");
    start_tolerance = prm.get_double("Start penetration tolerance");
    prm.leave_subsection();
    require(factor > 0, "Contact/Penalty factor", "must be > 0");
    const auto &triangulation = discretization.dof_handler.get_triangulation();
    if (tolerance == 0 || start_tolerance == 0)
      {
        const double diameter = geometry::diameter(triangulation);
        if (tolerance == 0)
          tolerance = 1e-4 * diameter;
        if (start_tolerance == 0)
          start_tolerance = 1e-3 * diameter;
      }
    // Keys name active cells, whose numbering a mesh change redraws.
    mesh_changed = triangulation.signals.any_change.connect([this]() {
      states.clear();
      committed.clear();
      step_start.clear();
    });
  }


  template <int dim>
  std::unique_ptr<forces::Interface<dim>>
  PenaltyContact<dim>::create(ParameterHandler             &prm,
                              const forces::SceneData<dim> &scene)
  {
    auto obstacles = Obstacle<dim>::create_all(prm, scene.parameter_directory);
    if (obstacles.empty())
      return nullptr;
    prm.enter_subsection("Contact");
    const bool penalty = prm.get("Method") == "penalty";
    prm.leave_subsection();
    // A penalty force of (u, t) needs an integrator that takes one (and
    // the time of each evaluation, for obstacles that move); multipliers,
    // one that solves a step again when they moved. Others would ignore
    // the obstacles unseen.
    const std::string parameter = obstacles.front().slot + "/Shape";
    if (penalty)
      scene.refuse_unless(&forces::Capabilities::penalty_contact,
                          parameter,
                          "contact with obstacles by a penalty needs",
                          scene.can.taken_away);
    else
      scene.refuse_unless(
        &forces::Capabilities::augmented_lagrangian,
        parameter,
        "contact with obstacles by the augmented Lagrangian needs");
    // The penalty scales with the stiffest material.
    return std::make_unique<PenaltyContact<dim>>(
      prm,
      scene.discretization,
      std::move(obstacles),
      scene.largest_youngs_modulus());
  }


  template class PenaltyContact<1>;
  template class PenaltyContact<2>;
  template class PenaltyContact<3>;

  // Named so that it comes before 'self contact' in the scene's (name)
  // order, as it did when the scene built both by hand.
  TISSUEFEM_REGISTER_FORCE_CONTRIBUTION(
    PenaltyContact,
    "obstacle contact",
    "contact of the body's boundary with the rigid obstacles of 'Contact' "
    "(on when a slot names a shape).")
} // namespace tissuefem::contact
