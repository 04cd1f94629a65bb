// Wavemakers: a paddle driven so that it makes regular waves of a given height and period
// (docs/user-guide.md, "Making waves"): a piston (its x prescribed) or a flap (its angle about a
// hinge below the water). The stroke comes from linear wavemaker theory; the motion is a
// PrescribedMotion that the block builds.

#include <cmath>
#include <numbers>
#include <optional>

#include "fsi/scene/scene.hpp"
#include "scene_builder.hpp"

namespace fsi::scene {

namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;
}  // namespace

double PaddleWave::offset(double t) const {
  const double r = t < ramp_time ? t / ramp_time - std::sin(kTwoPi * t / ramp_time) / kTwoPi : 1.0;
  return 0.5 * stroke * r * std::sin(omega * t);
}

double PaddleWave::offset_rate(double t) const {
  const bool ramping = t < ramp_time;
  const double r = ramping ? t / ramp_time - std::sin(kTwoPi * t / ramp_time) / kTwoPi : 1.0;
  const double dr = ramping ? (1.0 - std::cos(kTwoPi * t / ramp_time)) / ramp_time : 0.0;
  return 0.5 * stroke * (dr * std::sin(omega * t) + r * omega * std::cos(omega * t));
}

double PaddleWave::flap_angle(double t) const {
  return -std::atan(offset(t) / hinge_depth);
}

double PaddleWave::flap_angle_rate(double t) const {
  const double x = offset(t);
  return -offset_rate(t) * hinge_depth / (hinge_depth * hinge_depth + x * x);
}

namespace {

// omega^2 = g k tanh(k h) by Newton from the larger of the deep- and shallow-water k (the
// function is increasing and convex in k, so Newton descends onto the root).
double wavenumber(double omega, double depth, double gravity) {
  const double target = omega * omega / gravity;
  double k = std::max(target, omega / std::sqrt(gravity * depth));
  for (int i = 0; i < 100; ++i) {
    const double t = std::tanh(k * depth);
    const double f = k * t - target;
    const double df = t + k * depth * (1.0 - t * t);
    const double step = f / df;
    k -= step;
    if (std::abs(step) <= 1e-15 * k) break;
  }
  return k;
}

// hinge_depth = 0: a piston.
PaddleWave paddle_wave(double height, double period, double depth, double hinge_depth,
                       double gravity, double ramp_time) {
  PaddleWave wave;
  wave.ramp_time = ramp_time;
  wave.height = height;
  wave.period = period;
  wave.depth = depth;
  wave.hinge_depth = hinge_depth;
  wave.omega = kTwoPi / period;
  const double k = wavenumber(wave.omega, depth, gravity);
  wave.wavenumber = k;
  wave.wavelength = kTwoPi / k;
  const double kh = k * depth;
  // The integral of X(z) / (S/2) cosh k(h - z) over the water (scene.hpp): sinh(kh) / k for a
  // piston; for a flap, whose X falls linearly to 0 at the hinge (depth l), sinh(kh) / k -
  // (cosh kh - cosh k(h - l)) / (l k^2). Every hyperbolic function is written as e^(kh)/2 times
  // decaying exponentials, which cancel in H / S: deep water (kh of hundreds) does not overflow.
  const double e2 = std::exp(-2.0 * kh);
  double moved = (1.0 - e2) / k;
  if (hinge_depth > 0.0) {
    const double deeper = std::exp(-k * hinge_depth) + std::exp(-k * (2.0 * depth - hinge_depth));
    moved -= ((1.0 + e2) - deeper) / (hinge_depth * k * k);
  }
  wave.height_per_stroke = 2.0 * k * (1.0 - e2) * moved / ((1.0 - e2 * e2) + 4.0 * kh * e2);
  wave.stroke = height / wave.height_per_stroke;
  wave.phase_speed = wave.omega / k;
  // c_g = c/2 (1 + 2kh / sinh 2kh), 2kh / sinh 2kh = 4kh e^(-2kh) / (1 - e^(-4kh)).
  wave.group_speed = 0.5 * wave.phase_speed * (1.0 + 4.0 * kh * e2 / (1.0 - e2 * e2));
  // Miche's limit of a progressive wave's steepness: H / lambda = 0.142 tanh(k h).
  wave.breaking_height = 0.142 * std::tanh(kh) * wave.wavelength;
  return wave;
}

}  // namespace

PaddleWave piston_wave(double height, double period, double depth, double gravity,
                       double ramp_time) {
  return paddle_wave(height, period, depth, 0.0, gravity, ramp_time);
}

PaddleWave flap_wave(double height, double period, double depth, double hinge_depth, double gravity,
                     double ramp_time) {
  return paddle_wave(height, period, depth, hinge_depth, gravity, ramp_time);
}

namespace detail {
namespace {

// The keys both wavemakers share, after the name and body.
std::vector<ParameterSpec> wave_keys(std::vector<ParameterSpec> more) {
  std::vector<ParameterSpec> keys = {
      element_name_spec(), text("body", "name of the paddle's RigidBody2D"),
      number("height", "m", "the wave height H to make (crest to trough)").positive(),
      number("period", "s", "the wave period T").positive(),
      number("depth", "m", "the still water depth h at the paddle").positive()};
  for (ParameterSpec& key : more)
    keys.push_back(std::move(key));
  keys.push_back(number("ramp_periods", "",
                        "periods over which the stroke grows from 0 (0: full stroke from t = 0, "
                        "a jump in the paddle's velocity)")
                     .at_least(0.0)
                     .with_default(2.0));
  return keys;
}

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
          wave_keys({}))
          .as_list()
          .planar(),
      block_spec(
          "FlapWavemaker",
          "Drives a RigidBody2D (the paddle, a flap hinged below the water) in rotation so that "
          "it makes regular waves of the given height and period: its angle is theta0 - "
          "atan(S/2 r(t) sin(omega t) / l), so that its point at the still surface travels "
          "S/2 r(t) sin(omega t) in x, l the hinge's depth below the still surface. The stroke S "
          "(at the surface) from linear flap-wavemaker theory (Dean & Dalrymple 1991): H/S = "
          "4 k sinh(kh) [sinh(kh)/k - (cosh kh - cosh k(h - l))/(l k^2)] / (sinh 2kh + 2kh), "
          "for a flap on the floor (l = h) 4 (sinh kh / kh)(kh sinh kh - cosh kh + 1) / "
          "(sinh 2kh + 2kh); k and r(t) as for PistonWavemaker. Pin the flap to the ground at "
          "its hinge with a RevoluteJoint (the block drives the angle only); below a hinge above "
          "the floor, a fixed wall (the Ground's mesh) closes the flume. A PrescribedMotion of "
          "the angle (1 row; a joint_force sensor on its name reads the driving torque). "
          "--check prints the stroke and the largest angle; a wave steeper than Miche's limit is "
          "refused.",
          wave_keys({number("hinge_depth", "m",
                            "the hinge's depth l below the still surface (absent: the depth, a "
                            "flap hinged on the floor)")
                         .positive()
                         .optional()}))
          .as_list()
          .planar(),
  };
}

// The wave a block asks for, or nullopt after a problem: no gravity, a wave that breaks, a
// hinge below the floor.
std::optional<PaddleWave> asked_wave(SceneBuilder& builder, const View& block, bool flap) {
  const double gravity = std::hypot(builder.scene.gravity[0], builder.scene.gravity[1]);
  if (!(gravity > 0.0)) {
    builder.problem(block.location(),
                    std::string(flap ? "a FlapWavemaker" : "a PistonWavemaker") +
                        " needs gravity (the waves' dispersion relation), and the scene has none",
                    "add Gravity { acceleration = [0, -9.81] }");
    return std::nullopt;
  }
  const auto text = [](double value) { return format_significant(value, 4); };
  const double depth = block.number("depth");
  const double ramp_time = block.number("ramp_periods") * block.number("period");
  double hinge_depth = 0.0;
  if (flap) {
    hinge_depth = block.has("hinge_depth") ? block.number("hinge_depth") : depth;
    if (hinge_depth > depth) {
      builder.problem(block.location("hinge_depth"),
                      "the hinge " + text(hinge_depth) +
                          " m below the still surface is under the " + "floor (depth " +
                          text(depth) + " m)",
                      "give a hinge_depth of at most the depth (or leave it out: a flap on the "
                      "floor)");
      return std::nullopt;
    }
  }
  const PaddleWave wave = paddle_wave(block.number("height"), block.number("period"), depth,
                                      hinge_depth, gravity, ramp_time);
  if (wave.height > wave.breaking_height) {
    builder.problem(
        block.location("height"),
        "a wave " + text(wave.height) + " m high and " + text(wave.wavelength) +
            " m long in water " + text(wave.depth) +
            " m deep is steeper than Miche's limit H = 0.142 tanh(kh) lambda = " +
            text(wave.breaking_height) + " m: it breaks at the paddle",
        "lower the height below " + text(wave.breaking_height) + " m, or lengthen the period");
    return std::nullopt;
  }
  return wave;
}

void build_wavemaker(SceneBuilder& builder, const View& block, bool flap) {
  const std::optional<PaddleWave> wave = asked_wave(builder, block, flap);
  if (!wave) return;
  const mbd::BodyId body = builder.find_body(block, "body");
  if (builder.model.is_beam(body)) {
    builder.problem(
        block.location("body"),
        "'" + block.string("body") + "' is an AncfBeam2D; a wavemaker's paddle is rigid",
        "give the paddle as a RigidBody2D (a line for its Mesh)");
    return;
  }
  mbd::PrescribedMotionSpec spec;
  spec.name = name_of(block);
  spec.body = body;
  if (flap) {
    const double theta0 = builder.model.body(body).angle;
    spec.coordinate = mbd::Coordinate::Angle;
    spec.position = [theta0, wave = *wave](double t) { return theta0 + wave.flap_angle(t); };
    spec.rate = [wave = *wave](double t) { return wave.flap_angle_rate(t); };
  } else {
    const double x0 = builder.model.body(body).position.x();
    spec.coordinate = mbd::Coordinate::X;
    spec.position = [x0, wave = *wave](double t) { return x0 + wave.offset(t); };
    spec.rate = [wave = *wave](double t) { return wave.offset_rate(t); };
  }
  spec.check_times = prescribed_motion_check_times(builder.end_time);
  builder.add_joint(block, [&] { return builder.model.add_prescribed_motion(spec); },
                    {.rows = 1, .body = body, .kind = "prescribed motion"});
  builder.scene.wavemakers.push_back({block.location(), *wave});
}

void build_wavemakers(SceneBuilder& builder) {
  builder.each("PistonWavemaker",
               [&](const View& block) { build_wavemaker(builder, block, false); });
  builder.each("FlapWavemaker", [&](const View& block) { build_wavemaker(builder, block, true); });
}

}  // namespace

ElementFamily wavemaker_family() {
  return {"wavemakers", wavemaker_blocks, {build_wavemakers}};
}

}  // namespace detail
}  // namespace fsi::scene
