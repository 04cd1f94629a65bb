// Wavemakers: a piston paddle driven so that it makes regular waves of a given height and period
// (docs/user-guide.md, "Making waves: PistonWavemaker"). The stroke comes from linear
// wavemaker theory, the motion is a PrescribedMotion of the paddle's x that the block builds.

#include <cmath>
#include <numbers>

#include "fsi/scene/scene.hpp"
#include "scene_builder.hpp"

namespace fsi::scene {

namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;
}  // namespace

double PistonWave::offset(double t) const {
  const double r = t < ramp_time ? t / ramp_time - std::sin(kTwoPi * t / ramp_time) / kTwoPi : 1.0;
  return 0.5 * stroke * r * std::sin(omega * t);
}

double PistonWave::offset_rate(double t) const {
  const bool ramping = t < ramp_time;
  const double r = ramping ? t / ramp_time - std::sin(kTwoPi * t / ramp_time) / kTwoPi : 1.0;
  const double dr = ramping ? (1.0 - std::cos(kTwoPi * t / ramp_time)) / ramp_time : 0.0;
  return 0.5 * stroke * (dr * std::sin(omega * t) + r * omega * std::cos(omega * t));
}

PistonWave piston_wave(double height, double period, double depth, double gravity,
                       double ramp_time) {
  PistonWave wave;
  wave.ramp_time = ramp_time;
  wave.height = height;
  wave.period = period;
  wave.depth = depth;
  wave.omega = 2.0 * std::numbers::pi / period;
  // omega^2 = g k tanh(k h) by Newton from the deep-water k (the function is increasing in k).
  const double target = wave.omega * wave.omega / gravity;
  double k = std::max(target, wave.omega / std::sqrt(gravity * depth));
  for (int i = 0; i < 100; ++i) {
    const double t = std::tanh(k * depth);
    const double f = k * t - target;
    const double df = t + k * depth * (1.0 - t * t);
    const double step = f / df;
    k -= step;
    if (std::abs(step) <= 1e-15 * k) break;
  }
  wave.wavenumber = k;
  wave.wavelength = 2.0 * std::numbers::pi / k;
  const double kh = k * depth;
  // Linear piston wavemaker (Dean & Dalrymple 1991, eq. 6.23): H / S = 2 (cosh 2kh - 1) /
  // (sinh 2kh + 2kh).
  wave.height_per_stroke = 2.0 * (std::cosh(2.0 * kh) - 1.0) / (std::sinh(2.0 * kh) + 2.0 * kh);
  wave.stroke = height / wave.height_per_stroke;
  wave.phase_speed = wave.omega / k;
  wave.group_speed = 0.5 * wave.phase_speed * (1.0 + 2.0 * kh / std::sinh(2.0 * kh));
  // Miche's limit of a progressive wave's steepness: H / lambda = 0.142 tanh(k h).
  wave.breaking_height = 0.142 * std::tanh(kh) * wave.wavelength;
  return wave;
}

namespace detail {
namespace {

std::vector<BlockSpec> wavemaker_blocks() {
  return {
      block_spec(
          "PistonWavemaker",
          "Drives a RigidBody2D (the paddle, a vertical wall of the flume) along x so that it "
          "makes regular waves of the given height and period in water of the given depth: "
          "x(t) = x0 + S/2 r(t) sin(omega t), the stroke S from linear piston-wavemaker theory "
          "(Dean & Dalrymple 1991), H/S = 2 (cosh 2kh - 1) / (sinh 2kh + 2kh), k from omega^2 = "
          "g k tanh(kh) (g: the Gravity block), r(t) a smooth ramp from 0 to 1 over the first "
          "ramp_periods (r = r' = 0 at t = 0). It is a PrescribedMotion (1 row; a joint_force "
          "sensor on its name reads the force that drives the paddle); hold the paddle's y and "
          "angle with CoordinateConstraints. --check prints the stroke, the wavelength and the "
          "speeds; a wave steeper than Miche's breaking limit is refused.",
          {element_name_spec(), text("body", "name of the paddle's RigidBody2D"),
           number("height", "m", "the wave height H to make (crest to trough)").positive(),
           number("period", "s", "the wave period T").positive(),
           number("depth", "m", "the still water depth h at the paddle").positive(),
           number("ramp_periods", "",
                  "periods over which the stroke grows from 0 (0: full stroke from t = 0, a "
                  "jump in the paddle's velocity)")
               .at_least(0.0)
               .with_default(2.0)})
          .as_list()
          .planar(),
  };
}

void build_wavemakers(SceneBuilder& builder) {
  builder.each("PistonWavemaker", [&](const View& block) {
    const double gravity = std::hypot(builder.scene.gravity[0], builder.scene.gravity[1]);
    if (!(gravity > 0.0)) {
      builder.problem(block.location(),
                      "a PistonWavemaker needs gravity (the waves' dispersion relation), and the "
                      "scene has none",
                      "add Gravity { acceleration = [0, -9.81] }");
      return;
    }
    const PistonWave wave =
        piston_wave(block.number("height"), block.number("period"), block.number("depth"), gravity,
                    block.number("ramp_periods") * block.number("period"));
    if (wave.height > wave.breaking_height) {
      const auto text = [](double value) { return format_significant(value, 4); };
      builder.problem(
          block.location("height"),
          "a wave " + text(wave.height) + " m high and " + text(wave.wavelength) +
              " m long in water " + text(wave.depth) +
              " m deep is steeper than Miche's limit H = 0.142 tanh(kh) lambda = " +
              text(wave.breaking_height) + " m: it breaks at the paddle",
          "lower the height below " + text(wave.breaking_height) + " m, or lengthen the period");
      return;
    }
    const mbd::BodyId body = builder.find_body(block, "body");
    if (builder.model.is_beam(body)) {
      builder.problem(block.location("body"),
                      "'" + block.string("body") + "' is an AncfBeam2D; a piston paddle is rigid",
                      "give the paddle as a RigidBody2D (a vertical line for its Mesh)");
      return;
    }
    const double x0 = builder.model.body(body).position.x();
    mbd::PrescribedMotionSpec spec;
    spec.name = name_of(block);
    spec.body = body;
    spec.coordinate = mbd::Coordinate::X;
    spec.position = [x0, wave](double t) { return x0 + wave.offset(t); };
    spec.rate = [wave](double t) { return wave.offset_rate(t); };
    spec.check_times = prescribed_motion_check_times(builder.end_time);
    builder.add_joint(block, [&] { return builder.model.add_prescribed_motion(spec); },
                      {.rows = 1, .body = body, .kind = "prescribed motion"});
    builder.scene.wavemakers.push_back({block.location(), wave});
  });
}

}  // namespace

ElementFamily wavemaker_family() {
  return {"wavemakers", wavemaker_blocks, {build_wavemakers}};
}

}  // namespace detail
}  // namespace fsi::scene
