#pragma once
// A scene: everything fsi-server needs for one coupled run, built from a parameter file
// (docs/parameters.md is generated from scene_schema()).

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fsi/mbd/assembly.hpp"
#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/model.hpp"
#include "fsi/probes/probe.hpp"
#include "fsi/scene/fluid_parameters.hpp"
#include "fsi/scene/parameter_file.hpp"
#include "fsi/scene/schema.hpp"

namespace fsi::scene {

// SolverOptions.Timeint.method: how the multibody system is integrated. A coupled run always
// takes the fixed step (the fluid's); the error-controlled methods serve --mbd-only runs, which
// write their sensors every step_size.
enum class IntegrationMethod {
  FixedStep,      // the tableau (Radau IIA or Lobatto IIIA) at step_size
  AdaptiveRadau,  // the same tableau, step size by step doubling (fsi/mbd/adaptive_radau.hpp)
  Ida             // SUNDIALS IDA, BDF orders 1-5 (fsi/mbd/ida.hpp)
};

struct SolverSettings {
  double end_time = 0.0;
  double step_size = 0.0;  // the coupled (fluid) step
  // Where the step comes from: Timeint.step_size, or, when the scene leaves it out, the Fluid
  // block whose time-step rule derived it (`derived_time_step`, docs/user-guide.md).
  SourceLocation step_size_location;
  bool step_size_derived = false;
  int stages = 3;
  SourceLocation stages_location;
  // Multi-rate coupling: fluid steps per structure step (the structure steps substeps *
  // step_size; 1: both step together).
  int substeps = 1;
  SourceLocation substeps_location;
  // Multi-rate: the structure moves under the fluid's average force extrapolated linearly over
  // the (substeps - 1) fluid steps it lags (docs/theory.md, "Multi-rate coupling").
  bool linear_force_predictor = false;
  mbd::TableauFamily family = mbd::TableauFamily::RadauIIA;
  mbd::NewtonOptions newton;
  mbd::ConstraintForm constraint_form = mbd::ConstraintForm::Index3;
  IntegrationMethod method = IntegrationMethod::FixedStep;
  SourceLocation method_location;  // where the scene chose it, for messages
  // SolverOptions.ErrorControl: the local error test of the error-controlled methods.
  double relative_tolerance = 1e-6;
  double absolute_tolerance = 1e-8;
  double max_step = 0.0;  // [s]; 0: no limit

  // The fixed-step integrator these settings ask for (also the adaptive method's stepper).
  mbd::RadauOptions integrator_options() const { return {stages, newton, family, constraint_form}; }
  // The integrator's name for logs and run.json ("Radau IIA, 3 stages"; ", index-2 constraints"
  // when so; "adaptive ..." and "SUNDIALS IDA ..." with their tolerances); valid before any
  // integrator exists. `coupled`: what a coupled run integrates with (always the fixed step).
  std::string integrator_description(bool coupled = false) const;
  // The steps a run takes: round(end_time / step_size), for the coupled loop, --mbd-only and
  // the --check warning when the step does not divide end_time.
  std::uint64_t step_count() const;
};

struct OutputSettings {
  long sensor_every_steps = 1;
  long snapshot_every_steps = 0;  // 0: no particle snapshots
  // Checkpoints of both sides (issue 16): every N coupled steps (0: not by steps) and when this
  // much wall-clock time has passed since the last one (0: not by time).
  long checkpoint_every_steps = 0;
  double checkpoint_every_seconds = 1800.0;
};

// The structure's surface as the fluid sees it. 2D: mesh vertex k is model marker k; dynamic
// vertices (on bodies) come first, static ones (ground) after (thesis §5.2). 3D: the dynamic
// vertices are the spatial model's markers (meshes of RigidBody3D, tubes of AncfCable3D), the
// static ones (Ground STL meshes) are held in static_positions, not in the model.
struct BoundaryMesh {
  int dimension = 2;
  std::size_t vertex_count = 0;
  std::size_t dynamic_vertex_count = 0;
  std::vector<std::uint32_t> segments;   // 2D: two vertex indices each
  std::vector<std::uint32_t> triangles;  // 3D: three vertex indices each
  // 3D: x, y, z per static (ground) vertex, world coordinates; these vertices follow the
  // dynamic ones (markers of the model).
  std::vector<double> static_positions;
  // The elements the fluid sees: segments in 2D, triangles in 3D.
  const std::vector<std::uint32_t>& elements() const {
    return dimension == 3 ? triangles : segments;
  }
  std::size_t element_count() const {
    return elements().size() / static_cast<std::size_t>(dimension);
  }
  double refinement_resolution = 0.0;
  int refinement_option = 1;
};

// Positions and velocities of every boundary vertex at `state`, `dimension` values each: the
// dynamic vertices (the model's markers) first, then, in 3D, the static ground vertices (at
// rest). Resizes the vectors to dimension * vertex_count.
void boundary_state(const BoundaryMesh& boundary, const mbd::Model& model, const mbd::State& state,
                    std::vector<double>& positions, std::vector<double>& velocities);

// The body carrying boundary vertex `v`: its marker's body for a dynamic vertex, the ground for
// a static one.
mbd::BodyId vertex_body(const BoundaryMesh& boundary, const mbd::Model& model, std::uint32_t v);

// The boundary's elements (segments in 2D, triangles in 3D) grouped by the body carrying each
// (its first vertex's), the bodies in the order their first element comes: the one place that
// says which body an element belongs to (the crossing watch, the fluid-overlap check and the
// energy audit's books all ask it).
struct BodyElements {
  mbd::BodyId body = mbd::kGround;
  std::vector<std::uint32_t> elements;  // dimension vertex indices each, as in BoundaryMesh
};
std::vector<BodyElements> elements_by_body(const BoundaryMesh& boundary, const mbd::Model& model);

// A probe that moves with a rigid body: its index in Scene::probes and its body.
struct AttachedProbe {
  std::size_t probe = 0;
  mbd::BodyId body = mbd::kGround;
};

// The rigid motion of a rigid body (2D or 3D) from the model's initial configuration to
// `state`: x -> R x + b carries a point fixed to the body from where it started to where it is.
probes::RigidPlacement rigid_placement(const mbd::Model& model, const mbd::State& state,
                                       mbd::BodyId body);

struct Scene;
// Every attached probe of the scene placed where its body is at `state` (fsi::probes::placed),
// in the order of Scene::attached_probes.
std::vector<probes::ProbeDefinition> placed_probes(const Scene& scene, const mbd::State& state);

struct FluidParticles {
  int dimension = 2;
  int atom_type = 1;
  double mass = 0.0;  // per particle (2D: per unit depth)
  double density = 0.0;
  double spacing = 0.0;
  double column_height = 0.0;  // H along gravity (lattice_column_height); 0 without gravity
  // One initial density per particle (FluidRegion.hydrostatic = 1); empty: all start at density.
  std::vector<double> densities;
  std::vector<double> positions;  // dimension values per particle (x, y or x, y, z)
  std::vector<double> velocities;
  std::size_t count() const { return positions.size() / static_cast<std::size_t>(dimension); }
};

struct LiggghtsSetup {
  std::vector<std::pair<std::string, std::string>> variables;  // LIGGGHTS_SPH_parameters
  std::string script1_name, script1_text;
  std::string script2_name, script2_text;
  std::uint64_t equilibration_steps = 0;
  // The drag rate [1/s] of the equilibration's settling (docs/theory.md, "Settling the fluid"):
  // absent = derived by fsi-client from H, |g| and dt; 0 = none.
  std::optional<double> settling_drag;
  // Particles the run may lose (leave the LIGGGHTS box) before it fails.
  std::uint64_t allowed_lost_particles = 0;
};

// The limits of the fluid health checks that stop a coupled run (block FluidHealth;
// docs/user-guide.md, "When a run stops: the health checks"). The defaults are the block's.
struct FluidHealthLimits {
  double max_density_deviation = 0.03;   // stop above: max |rho/rho0 - 1|
  double warn_density_deviation = 0.01;  // warn above (the aim of weakly compressible SPH)
  double max_mach = 0.5;                 // stop above: max |v| / c
  double warn_mach = 0.1;                // warn above (c >= 10 v_max, thesis §6.2)
  double min_wall_distance = 0.1;        // stop below: closest particle-wall distance / r0
  // stop above: the energy the coupling created / its value at the energy audit's warning
  // (fsi/coupling/energy_audit.hpp); 0 = never
  double max_coupling_energy_growth = 3.0;
};

// TotalFluidForce: the force of the fluid on every boundary, static walls included (no body).
// JointForce: force and torque a joint's rows exert on its body (-G^T lambda of those rows);
// SpringForce: a spring's tension or a rotational spring's torque; the energies are the system's
// (potential: gravity plus the springs' elastic energy).
enum class SensorType {
  Position,
  Velocity,
  FluidForce,
  ConstraintForce,
  TotalFluidForce,
  JointForce,
  SpringForce,
  KineticEnergy,
  PotentialEnergy,
  StrainEnergy,
  ChordDeflection,  // a beam point's distance from the chord through the beam's ends
  Power,            // the rate of work a named spring or damper does on the bodies
  Work              // its time integral from t = 0 (accumulated over the steps by the run)
};

// SensorSpec::axis of a driven RevoluteJoint3D's drive torque.
inline constexpr int kDriveTorqueAxis = 6;

struct SensorSpec {
  std::string name;
  SensorType type = SensorType::Position;
  mbd::BodyId body = 0;                            // unused for TotalFluidForce and energies
  mbd::Coordinate component = mbd::Coordinate::X;  // Angle means the torque for force sensors
  // TotalFluidForce and 3D sensors: 0 x, 1 y, 2 z, 3-5 torque x, y, z; a 2D point: 0 x, 1 y;
  // kDriveTorqueAxis: a 3D JointForce's component torque, the drive torque of a driven
  // RevoluteJoint3D about its axis on body_a (the multiplier of its last row).
  int axis = 0;
  // Position, velocity: a body point instead of the centre of mass (2D: z = 0).
  std::optional<std::array<double, 3>> point;
  std::string unit;
  int first_row = 0;  // JointForce: the joint's constraint rows
  int rows = 0;
  // JointForce of a joint on an AncfBeam2D `body`: the beam point [s, eta] it acts at (a
  // BeamClamp's node, a pin's point_a); the torque is about that point.
  std::optional<std::array<double, 2>> beam_point;
  int force_element = -1;  // SpringForce, Power, Work: index among the model's force elements
  // Planar position, velocity: the components in the axes of this rigid body, from its centre of
  // mass (an angle relative to its angle) instead of the world's.
  std::optional<mbd::BodyId> frame;
  // FluidForce, JointForce, ConstraintForce of a rigid body: its torque about this body point
  // (body coordinates; 2D: z = 0), tau_P = tau_G + (r_G - r_P) x F, instead of about the centre
  // of mass G (a gate's moment about its hinge).
  std::optional<std::array<double, 3>> about;
};

// The value of a sensor that the multibody state alone determines (every type but
// TotalFluidForce and Work, whose value depends on the run's history; FluidForce from the point
// loads set on the model).
double structure_sensor_value(const mbd::Model& model, const SensorSpec& sensor,
                              const mbd::State& state);

// Waves of a wavemaker paddle by linear theory (blocks PistonWavemaker and FlapWavemaker;
// docs/user-guide.md, "Making waves"): omega^2 = g k tanh(k h); the paddle moves the water at
// depth z below the still surface by X(z) = S/2 sin(omega t) for a piston, X(z) = S/2 (1 - z/l)
// above a flap's hinge at depth l (0 below it), and the progressive wave's height is
// H = 4 k sinh(kh) / (sinh 2kh + 2kh) times the integral of X(z)/(S/2) cosh k(h - z) over the depth
// (Dean & Dalrymple 1991, §6.2): H / S = 2 (cosh 2kh - 1) / (sinh 2kh + 2kh) for a piston.
// Irregular waves are a sum of such regular components, each with its own stroke.
struct WaveComponent {
  double omega = 0.0;        // [1/s]
  double height = 0.0;       // the component's wave height, twice its amplitude [m]
  double half_stroke = 0.0;  // S_i / 2 at the still surface [m]
  double phase = 0.0;        // [rad]
};
struct PaddleWave {
  // Regular: H, T; irregular (spectrum "jonswap"): the significant height H_m0 = 4 sqrt(m0) and
  // the peak period T_p, and every other scalar below is the peak frequency's.
  double height = 0.0, period = 0.0, depth = 0.0;  // H [m], T [s], h [m]
  double hinge_depth = 0.0;                        // l: a flap's hinge below the surface; 0: piston
  double omega = 0.0;                              // 2 pi / T [1/s]
  double wavenumber = 0.0, wavelength = 0.0;       // k [1/m], 2 pi / k [m]
  double height_per_stroke = 0.0;                  // H / S
  double stroke = 0.0;  // S: the paddle's full travel at the still surface [m]
  double phase_speed = 0.0, group_speed = 0.0;  // omega / k, d omega / dk [m/s]
  double breaking_height = 0.0;                 // Miche: 0.142 tanh(kh) lambda [m]
  double ramp_time = 0.0;                       // the stroke grows over [0, ramp_time] [s]
  // The motion: one component (phase 0) for regular waves, many for a spectrum.
  std::vector<WaveComponent> components;
  std::string spectrum = "regular";  // or "jonswap"
  double peak_enhancement = 1.0;     // JONSWAP's gamma
  double repeat_period = 0.0;        // 2 pi / (the components' spacing); regular: T
  double largest_offset = 0.0;       // max |offset| over a repeat period, ramp done [m]
  bool flap() const { return hinge_depth > 0.0; }
  // The paddle's displacement from rest at the still surface, r(t) sum S_i/2 sin(omega_i t +
  // phi_i), r = t/Tr - sin(2 pi t/Tr)/(2 pi) for t < Tr = ramp_time, else 1 (r(0) = r'(0) = 0,
  // r' continuous), and its rate.
  double offset(double time) const;
  double offset_rate(double time) const;
  // A flap's rotation from rest that moves the still surface's point of it by offset(t),
  // -atan(offset / l) (counterclockwise positive: the top moves toward +x for a negative angle),
  // and its rate.
  double flap_angle(double time) const;
  double flap_angle_rate(double time) const;
};
PaddleWave piston_wave(double height, double period, double depth, double gravity,
                       double ramp_time = 0.0);
// A flap hinged hinge_depth below the still surface (hinge_depth = depth: on the floor).
PaddleWave flap_wave(double height, double period, double depth, double hinge_depth, double gravity,
                     double ramp_time = 0.0);
// An irregular sea of a JONSWAP spectrum (DNV-RP-C205 §3.5.5: S(omega) = (1 - 0.287 ln gamma)
// 5/16 Hs^2 wp^4 omega^-5 exp(-5/4 (omega/wp)^-4) gamma^exp(-(omega - wp)^2 / (2 sigma^2 wp^2)),
// sigma 0.07 below wp and 0.09 above; gamma = 1: Pierson-Moskowitz) made by `count` components at
// the middles of equal bands over [band_low, band_high] times the peak frequency (moved by less
// than half a band so that each is a whole multiple of the band's width: the sea repeats after
// 2 pi / width), each of height 2 sqrt(2 S(omega_i) d omega) scaled so that 4 sqrt(m0) of the
// sum is Hs exactly, its phase drawn from a 64-bit Mersenne twister seeded with `seed` (the same
// on every machine). The sea's Hs is judged against Miche's limit at T_p like a regular wave's H;
// its highest waves (about 1.9 Hs) may still break.
struct SpectrumRequest {
  double significant_height = 0.0, peak_period = 0.0, gamma = 3.3;
  int count = 64;
  double band_low = 0.5, band_high = 3.0;
  std::uint64_t seed = 1;
};
PaddleWave irregular_wave(const SpectrumRequest& request, double depth, double hinge_depth,
                          double gravity, double ramp_time = 0.0);

struct PlacedWavemaker {
  SourceLocation location;
  std::string name;  // "" when unnamed
  std::string body;  // the paddle
  PaddleWave wave;
};

// A box where the fluid is slowed during the coupled run by a velocity drag -rate s^2 m v (block
// DampingZone; docs/user-guide.md, "Absorbing waves: DampingZone"): s grows from 0 at the box's
// side opposite the strong one to 1 at the strong side (uniform: 1 everywhere).
struct DampingZone {
  SourceLocation location;
  std::array<double, 3> lower{}, upper{};  // 2D: z unused
  double rate = 0.0;                       // lambda at s = 1 [1/s]
  int axis = -1;                           // 0, 1, 2: s grows along it; -1: uniform
  bool toward_upper = true;                // s = 1 at upper[axis] (else at lower[axis])
};

// The LIGGGHTS commands of the damping zones (a region, atom-style variables and a fix addforce
// per zone, IDs fsi_damping_K): fsi-server appends them to script 2, so that they act from the
// coupled run's first step. "" without zones.
std::string damping_zone_commands(const std::vector<DampingZone>& zones, int dimension);

struct Scene;
// Script 2 as fsi-server sends it: the scene's script 2, then its damping zones' commands.
std::string script2_sent(const Scene& scene);

struct Scene {
  std::string file;
  Block parameters;                 // the evaluated parameter tree
  int dimension = 2;                // root parameter `dimension`; 3: spatial bodies and STL meshes
  std::array<double, 3> gravity{};  // Gravity.acceleration (2D: z = 0; the model holds x, y)
  mbd::Model model;
  SolverSettings solver;
  OutputSettings output;
  BoundaryMesh boundary;
  FluidParticles fluid;
  LiggghtsSetup liggghts;
  FluidHealthLimits health;
  std::vector<SensorSpec> sensors;
  // The probes of the fluid (coupled runs): their columns follow the sensors' in sensors.csv.
  // Each is declared where it is in the initial configuration.
  std::vector<probes::ProbeDefinition> probes;
  // The probes that move with a rigid body (`body = "NAME"`), placed at every probe step
  // (placed_probes below; protocol 1.4).
  std::vector<AttachedProbe> attached_probes;
  // What the Assembly block's initial assembly did (absent without the block); the model's
  // initial configuration is then the assembled one.
  std::optional<mbd::AssemblyReport> assembly;
  // The pairs of bodies (mbd::kGround for the ground) whose meshes have a Contact block between
  // them; the run's crossing check (mesh_crossing.hpp) watches the other pairs.
  std::vector<std::pair<mbd::BodyId, mbd::BodyId>> contact_pairs;
  // The Fluid block's values (absent without one; docs/user-guide.md, "The Fluid block"): they
  // become LIGGGHTS variables next to the LIGGGHTS_SPH_parameters, and --check explains each.
  std::optional<FluidDerivation> fluid_parameters;
  // The same values as parameters named by their LIGGGHTS variable, each at the Fluid key that
  // sets it (or the Fluid block for a derived one): what sph_parameter finds.
  std::vector<Parameter> fluid_variables;
  // The DampingZone blocks, in order.
  std::vector<DampingZone> damping_zones;
  // The PistonWavemaker blocks' waves, in order (each drives its paddle by a PrescribedMotion).
  std::vector<PlacedWavemaker> wavemakers;
};

// A LIGGGHTS variable the scene defines by name: an entry of LIGGGHTS_SPH_parameters, else a value
// of the Fluid block; nullptr when neither has it. The physics checks read variables through it.
const Parameter* sph_parameter(const Scene& scene, std::string_view name);

// The declaration of every scene parameter, block by block in the order of the element families
// (src/family_registry.cpp).
const BlockSpec& scene_schema();

// What a scene is built for. A coupled run needs the fluid's blocks (a surface mesh, LIGGGHTS,
// Coupling); a run of the multibody system alone (`fsi-server --mbd-only`) needs none of them.
enum class SceneMode { Coupled, MbdOnly };

// Loads, validates (all problems at once) and builds a scene. A scene must state its language
// version (`scene_language = 1` as its first entry). Throws fsi::Error.
Scene build_scene(const std::string& path, const std::vector<Override>& overrides = {},
                  SceneMode mode = SceneMode::Coupled);

// How much of a box FluidRegion its lattice fills, for --check's summary and the run's log: the
// box is filled with whole cells of the spacing d from its lower corner, so an extent that is
// not a whole number of spacings leaves up to d of it empty at the upper side (the water is
// shallower or narrower than drawn). "" when every extent is within d/4 of whole cells or the
// region is not a box.
std::string fluid_box_fill(const Scene& scene);

// Which blocks a run in `mode` needs of this scene and which of the given ones it does not read,
// a few lines of text for `fsi-server --check`.
std::string blocks_needed(const Scene& scene, SceneMode mode);

}  // namespace fsi::scene
