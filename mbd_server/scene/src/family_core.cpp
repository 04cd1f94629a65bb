// The core of every scene: solver settings, output, gravity.

#include "scene_builder.hpp"

namespace fsi::scene::detail {
namespace {

BlockSpec timeint_spec() {
  return block_spec(
      "Timeint", "Time integration of the multibody system (fixed step when coupled).",
      {number("step_size", "s",
              "coupled time step, the same on both sides; SPH needs <= 0.125 h/c; "
              "--mbd-only with an error-controlled method: the output step; absent in a "
              "coupled scene with a Fluid block: the largest step within the block's "
              "time-step rule that divides end_time into whole structure steps "
              "(docs/user-guide.md, \"The Fluid block\")")
           .positive()
           .optional(),
       text("method",
            "fixed: the tableau at step_size; adaptive: the tableau with step-doubling "
            "error control; ida: SUNDIALS IDA (BDF 1-5); the last two for --mbd-only "
            "(ErrorControl), a coupled run always takes the fixed step")
           .one_of({"fixed", "adaptive", "ida"})
           .with_default("fixed"),
       text("tableau", "implicit Runge-Kutta scheme (HOTINT's tableau_name)")
           .one_of({"RadauIIA", "LobattoIIIA"})
           .with_default("RadauIIA"),
       integer("stages",
               "Radau IIA: 1, 2, 3 (orders 1, 3, 5; 1 is implicit Euler, which damps "
               "oscillations: --check states how much); Lobatto IIIA: 2, 3 (orders 2, 4 on "
               "free bodies; 2 and 2 on constrained ones, docs/theory.md)")
           .with_default(3)
           .between(1, 3),
       integer("substeps",
               "multi-rate coupling: fluid steps of step_size per structure step; the "
               "structure steps k * step_size and the walls move on its stage values in "
               "between (docs/theory.md, \"Multi-rate coupling\"); coupled runs only, "
               "--mbd-only steps at step_size")
           .with_default(1)
           .between(1, 1000),
       text("force_predictor",
            "multi-rate coupling: none holds the fluid's average force of the last k "
            "fluid steps over the structure step; linear extrapolates it over the k - 1 "
            "steps it lags, from the last two averages (docs/theory.md, \"Multi-rate "
            "coupling\"); no effect with substeps = 1")
           .one_of({"none", "linear"})
           .with_default("none"),
       text("constraint_form",
            "index3: position constraints C = 0 at the stages (no drift); index2: their "
            "rates G v + dC/dt = 0 (positions drift by the integration error; HOTINT's "
            "alternative)")
           .one_of({"index3", "index2"})
           .with_default("index3")});
  // Not required: every key has a default but step_size, which a Fluid block may derive (a
  // scene without either is told so at SolverOptions).
}

BlockSpec newton_spec() {
  return block_spec(
      "Newton", "Newton iterations of the implicit stage equations.",
      {number("relative_tolerance", "", "increment tolerance relative to the stage values")
           .positive()
           .with_default(1e-10),
       integer("max_iterations", "iterations before the step fails").at_least(1).with_default(12),
       integer("max_modified_newton_steps",
               "steps that reuse one factorised Jacobian (0: full Newton)")
           .at_least(0)
           .with_default(20),
       number("max_contraction", "",
              "a reused Jacobian is replaced when |dx_k|/|dx_k-1| exceeds this")
           .above(0.0)
           .at_most(1.0)
           .with_default(0.5),
       number("absolute_tolerance", "SI", "increment tolerance where a whole block stays zero")
           .positive()
           .with_default(1e-14)});
}

BlockSpec error_control_spec() {
  return block_spec(
      "ErrorControl",
      "Local error test of Timeint.method = adaptive or ida (--mbd-only): per coordinate and "
      "velocity |e| <= relative_tolerance |y| + absolute_tolerance (weighted RMS).",
      {number("relative_tolerance", "", "relative local error").positive().with_default(1e-6),
       number("absolute_tolerance", "SI", "absolute local error").positive().with_default(1e-8),
       number("max_step", "s", "largest step (0: no limit)").at_least(0.0).with_default(0.0)});
}

std::vector<BlockSpec> core_blocks() {
  return {
      block_spec("SolverOptions", "Solver settings of the run.",
                 {number("end_time", "s", "simulated time of the coupled phase").positive()},
                 {timeint_spec(), newton_spec(), error_control_spec()})
          .as_required(),
      block_spec("Output", "What the server writes into the output folder.",
                 {integer("sensor_every_steps", "write a sensors.csv row every N steps")
                      .at_least(1)
                      .with_default(1),
                  integer("snapshot_every_steps",
                          "request an SPH particle snapshot every N steps (0: never)")
                      .at_least(0)
                      .with_default(0),
                  integer("checkpoint_every_steps",
                          "write a checkpoint of both sides every N steps, the newest two kept "
                          "in OUTPUT/checkpoints (0: not by steps; docs/user-guide.md, "
                          "\"Checkpoints and resume\")")
                      .at_least(0)
                      .with_default(0),
                  number("checkpoint_every_seconds", "s",
                         "also write a checkpoint when this much wall-clock time has passed "
                         "since the last one (0: not by time)")
                      .at_least(0.0)
                      .with_default(1800.0)}),
      block_spec("Gravity", "Uniform gravitational acceleration.",
                 {per_dimension(vector("acceleration", 2, "m/s^2",
                                       "acceleration vector ([x, y]; 3D: [x, y, z], default 0)"))
                      .with_default({0.0, 0.0})}),
  };
}

void build_solver(SceneBuilder& builder) {
  SolverSettings& solver = builder.scene.solver;
  const View options = builder.root.block("SolverOptions");
  const View timeint = options.block("Timeint");
  solver.end_time = options.number("end_time");
  builder.end_time = solver.end_time;
  // Absent: the Fluid block derives it (family_fluid_parameters.cpp), or that family reports it.
  if (timeint.has("step_size")) {
    solver.step_size = timeint.number("step_size");
    solver.step_size_location = timeint.location("step_size");
  }
  solver.stages = static_cast<int>(timeint.integer("stages"));
  solver.stages_location = timeint.location("stages");
  solver.substeps = static_cast<int>(timeint.integer("substeps"));
  solver.substeps_location = timeint.location("substeps");
  solver.linear_force_predictor = timeint.string("force_predictor") == "linear";
  const bool lobatto = timeint.string("tableau") == "LobattoIIIA";
  solver.constraint_form = timeint.string("constraint_form") == "index2"
                               ? mbd::ConstraintForm::Index2
                               : mbd::ConstraintForm::Index3;
  solver.family = lobatto ? mbd::TableauFamily::LobattoIIIA : mbd::TableauFamily::RadauIIA;
  const std::string& method = timeint.string("method");
  solver.method = method == "adaptive" ? IntegrationMethod::AdaptiveRadau
                  : method == "ida"    ? IntegrationMethod::Ida
                                       : IntegrationMethod::FixedStep;
  solver.method_location = timeint.location("method");
  const View error_control = options.block("ErrorControl");
  solver.relative_tolerance = error_control.number("relative_tolerance");
  solver.absolute_tolerance = error_control.number("absolute_tolerance");
  solver.max_step = error_control.number("max_step");
  if (lobatto && solver.stages < 2) {
    builder.problem(timeint.location("stages"),
                    "Lobatto IIIA has 2 or 3 stages, not " + std::to_string(solver.stages),
                    "write stages = 2 or 3 (order 2 on constrained bodies either way; 3 reaches "
                    "order 4 on unconstrained ones)");
  }
  const View newton = options.block("Newton");
  solver.newton.relative_tolerance = newton.number("relative_tolerance");
  solver.newton.max_iterations = static_cast<int>(newton.integer("max_iterations"));
  solver.newton.max_modified_newton_steps =
      static_cast<int>(newton.integer("max_modified_newton_steps"));
  solver.newton.max_contraction = newton.number("max_contraction");
  solver.newton.absolute_tolerance = newton.number("absolute_tolerance");
}

// Multi-rate coupling: the structure's state exists at the ends of its steps only, so the rows,
// snapshots and the end fall there.
void check_substeps(SceneBuilder& builder) {
  const Scene& scene = builder.scene;
  const long k = scene.solver.substeps;
  if (k <= 1) return;
  const std::string fix_hint = " (SolverOptions.Timeint.substeps = " + std::to_string(k) + ")";
  if (scene.output.sensor_every_steps % k != 0) {
    builder.problem(
        scene.solver.substeps_location,
        "Output.sensor_every_steps = " + std::to_string(scene.output.sensor_every_steps) +
            " is not a multiple of the substeps" + fix_hint +
            ": sensor rows are written at the ends of structure steps",
        "make sensor_every_steps a multiple of substeps");
  }
  if (scene.output.snapshot_every_steps % k != 0) {
    builder.problem(
        scene.solver.substeps_location,
        "Output.snapshot_every_steps = " + std::to_string(scene.output.snapshot_every_steps) +
            " is not a multiple of the substeps" + fix_hint,
        "make snapshot_every_steps a multiple of substeps (or 0)");
  }
  if (scene.output.checkpoint_every_steps % k != 0) {
    builder.problem(
        scene.solver.substeps_location,
        "Output.checkpoint_every_steps = " + std::to_string(scene.output.checkpoint_every_steps) +
            " is not a multiple of the substeps" + fix_hint +
            ": checkpoints are taken at the ends of structure steps",
        "make checkpoint_every_steps a multiple of substeps (or 0)");
  }
  // A step the Fluid block derives is a whole number of structure steps by construction.
  if (!(scene.solver.step_size > 0.0)) return;
  const std::uint64_t steps = scene.solver.step_count();
  if (steps % static_cast<std::uint64_t>(k) != 0) {
    builder.problem(scene.solver.substeps_location,
                    "the run's " + std::to_string(steps) +
                        " steps (SolverOptions.end_time / step_size) are not a multiple of the "
                        "substeps" +
                        fix_hint,
                    "choose end_time as a multiple of substeps * step_size");
  }
}

void build_core(SceneBuilder& builder) {
  const View& root = builder.root;
  Scene& scene = builder.scene;
  builder.guard(root.location(), [&] { build_solver(builder); });
  builder.guard(root.location(), [&] {
    scene.output.sensor_every_steps = root.block("Output").integer("sensor_every_steps");
    scene.output.snapshot_every_steps = root.block("Output").integer("snapshot_every_steps");
    scene.output.checkpoint_every_steps = root.block("Output").integer("checkpoint_every_steps");
    scene.output.checkpoint_every_seconds = root.block("Output").number("checkpoint_every_seconds");
    check_substeps(builder);
  });
  builder.guard(root.location(), [&] {
    const View gravity_block = root.block("Gravity");
    if (!gravity_block.has("acceleration")) return;  // default: none
    const auto gravity = builder.dimension_vector(gravity_block, "acceleration", builder.dimension);
    if (!gravity) return;
    for (std::size_t k = 0; k < gravity->size(); ++k)
      scene.gravity[k] = (*gravity)[k];
    if (builder.spatial()) {
      builder.model.set_spatial_gravity({scene.gravity[0], scene.gravity[1], scene.gravity[2]});
    } else {
      builder.model.set_gravity({scene.gravity[0], scene.gravity[1]});
    }
  });
}

}  // namespace

ElementFamily core_family() {
  return {"solver, output and gravity", core_blocks, {build_core}};
}

}  // namespace fsi::scene::detail
