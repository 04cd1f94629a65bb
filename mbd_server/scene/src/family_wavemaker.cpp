// Wavemakers: a paddle driven so that it makes regular waves of a given height and period, or an
// irregular sea of a JONSWAP spectrum (docs/user-guide.md, "Making waves"): a piston (its x
// prescribed) or a flap (its angle about a hinge below the water). Each wave component's stroke
// comes from linear wavemaker theory; the motion is a PrescribedMotion that the block builds.

#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <random>
#include <utility>

#include "fsi/common/error.hpp"
#include "fsi/common/text.hpp"
#include "fsi/scene/scene.hpp"
#include "scene_builder.hpp"

namespace fsi::scene {

namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;
}  // namespace

namespace {

// The ramp r(t) and its rate (scene.hpp).
std::pair<double, double> ramp(double t, double ramp_time) {
  if (!(t < ramp_time)) return {1.0, 0.0};
  return {t / ramp_time - std::sin(kTwoPi * t / ramp_time) / kTwoPi,
          (1.0 - std::cos(kTwoPi * t / ramp_time)) / ramp_time};
}

}  // namespace

double PaddleWave::offset(double t) const {
  double sum = 0.0;
  for (const WaveComponent& c : components)
    sum += c.half_stroke * std::sin(c.omega * t + c.phase);
  return ramp(t, ramp_time).first * sum;
}

double PaddleWave::offset_rate(double t) const {
  double sum = 0.0, rate = 0.0;
  for (const WaveComponent& c : components) {
    sum += c.half_stroke * std::sin(c.omega * t + c.phase);
    rate += c.half_stroke * c.omega * std::cos(c.omega * t + c.phase);
  }
  const auto [r, dr] = ramp(t, ramp_time);
  return dr * sum + r * rate;
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

// H / S of linear wavemaker theory at wavenumber k (hinge_depth = 0: a piston). The integral of
// X(z) / (S/2) cosh k(h - z) over the water (scene.hpp) is sinh(kh) / k for a piston; for a flap,
// whose X falls linearly to 0 at the hinge (depth l), sinh(kh) / k - (cosh kh - cosh k(h - l)) /
// (l k^2). Every hyperbolic function is written as e^(kh)/2 times decaying exponentials, which
// cancel in H / S: deep water (kh of hundreds) does not overflow.
double height_per_stroke(double k, double depth, double hinge_depth) {
  const double kh = k * depth;
  const double e2 = std::exp(-2.0 * kh);
  double moved = (1.0 - e2) / k;
  if (hinge_depth > 0.0) {
    const double deeper = std::exp(-k * hinge_depth) + std::exp(-k * (2.0 * depth - hinge_depth));
    moved -= ((1.0 + e2) - deeper) / (hinge_depth * k * k);
  }
  return 2.0 * k * (1.0 - e2) * moved / ((1.0 - e2 * e2) + 4.0 * kh * e2);
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
  wave.height_per_stroke = height_per_stroke(k, depth, hinge_depth);
  wave.stroke = height / wave.height_per_stroke;
  wave.phase_speed = wave.omega / k;
  // c_g = c/2 (1 + 2kh / sinh 2kh), 2kh / sinh 2kh = 4kh e^(-2kh) / (1 - e^(-4kh)).
  const double e2 = std::exp(-2.0 * kh);
  wave.group_speed = 0.5 * wave.phase_speed * (1.0 + 4.0 * kh * e2 / (1.0 - e2 * e2));
  // Miche's limit of a progressive wave's steepness: H / lambda = 0.142 tanh(k h).
  wave.breaking_height = 0.142 * std::tanh(kh) * wave.wavelength;
  wave.components = {{wave.omega, height, 0.5 * wave.stroke, 0.0}};
  wave.repeat_period = period;
  wave.largest_offset = 0.5 * wave.stroke;
  return wave;
}

// JONSWAP's spectral density at omega (scene.hpp), without the factor Hs^2 (scaled later).
double jonswap_shape(double omega, double peak_omega, double gamma) {
  const double ratio = omega / peak_omega;
  const double sigma = omega <= peak_omega ? 0.07 : 0.09;
  const double peak =
      std::exp(-std::pow(omega - peak_omega, 2) / (2.0 * sigma * sigma * peak_omega * peak_omega));
  return (1.0 - 0.287 * std::log(gamma)) * 5.0 / 16.0 * std::pow(peak_omega, 4) *
         std::pow(omega, -5.0) * std::exp(-1.25 * std::pow(ratio, -4.0)) * std::pow(gamma, peak);
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

PaddleWave irregular_wave(const SpectrumRequest& request, double depth, double hinge_depth,
                          double gravity, double ramp_time) {
  PaddleWave wave = paddle_wave(request.significant_height, request.peak_period, depth, hinge_depth,
                                gravity, ramp_time);
  wave.spectrum = "jonswap";
  wave.peak_enhancement = request.gamma;
  const double low = request.band_low * wave.omega, high = request.band_high * wave.omega;
  // Every frequency a whole multiple n spacing of the spacing, the first nearest the band's first
  // middle: the sea then repeats after 2 pi / spacing exactly.
  const double spacing = (high - low) / request.count;
  const double first = std::round(low / spacing + 0.5);
  wave.repeat_period = kTwoPi / spacing;
  // Phases from the generator's raw 64-bit output (std::uniform_real_distribution's algorithm is
  // the library's own; the engine's sequence is the standard's).
  std::mt19937_64 engine(request.seed);
  wave.components.clear();
  double variance = 0.0;  // m0 of the discrete sum: sum of a_i^2 / 2
  for (int i = 0; i < request.count; ++i) {
    WaveComponent c;
    c.omega = (first + i) * spacing;
    const double amplitude =
        std::sqrt(2.0 * jonswap_shape(c.omega, wave.omega, request.gamma) * spacing);
    c.height = 2.0 * amplitude;
    c.phase = kTwoPi * static_cast<double>(engine() >> 11) * 0x1.0p-53;
    variance += 0.5 * amplitude * amplitude;
    wave.components.push_back(c);
  }
  // 4 sqrt(m0) = Hs exactly (the continuous spectrum's A_gamma is an approximation, and the band
  // leaves out its tails).
  const double scale = request.significant_height / (4.0 * std::sqrt(variance));
  for (WaveComponent& c : wave.components) {
    c.height *= scale;
    c.half_stroke =
        0.5 * c.height / height_per_stroke(wavenumber(c.omega, depth, gravity), depth, hinge_depth);
  }
  // The largest excursion over one repeat period after the ramp, sampled at a twentieth of the
  // shortest component's period.
  const double step = kTwoPi / high / 20.0;
  double largest = 0.0;
  for (double t = ramp_time; t < ramp_time + wave.repeat_period; t += step)
    largest = std::max(largest, std::abs(wave.offset(t)));
  wave.largest_offset = largest;
  return wave;
}

namespace detail {
namespace {

// The keys both wavemakers share, after the name and body.
std::vector<ParameterSpec> wave_keys(std::vector<ParameterSpec> more) {
  std::vector<ParameterSpec> keys = {
      element_name_spec(), text("body", "name of the paddle's RigidBody2D"),
      number("height", "m",
             "the wave height H to make (crest to trough); spectrum jonswap: the significant "
             "height H_m0 = 4 sqrt(m0)")
          .positive(),
      number("period", "s", "the wave period T; spectrum jonswap: the peak period T_p").positive(),
      number("depth", "m", "the still water depth h at the paddle").positive()};
  for (ParameterSpec& key : more)
    keys.push_back(std::move(key));
  keys.push_back(number("ramp_periods", "",
                        "periods over which the stroke grows from 0 (0: full stroke from t = 0, "
                        "a jump in the paddle's velocity)")
                     .at_least(0.0)
                     .with_default(2.0));
  keys.push_back(text("spectrum",
                      "regular: one wave of height H and period T; jonswap: an irregular sea of "
                      "the JONSWAP spectrum of significant height `height` and peak period "
                      "`period` (DNV-RP-C205), a sum of `components` regular waves with random "
                      "phases, each with the stroke linear theory gives it")
                     .one_of({"regular", "jonswap"})
                     .with_default("regular"));
  keys.push_back(number("gamma", "",
                        "jonswap: the peak enhancement factor (1: Pierson-Moskowitz; default 3.3)")
                     .between(1.0, 10.0)
                     .optional());
  keys.push_back(integer("components",
                         "jonswap: regular components at the middles of equal frequency bands "
                         "(default 64); the sea repeats after 2 pi / (the band's width), printed")
                     .between(2, 4096)
                     .optional());
  keys.push_back(vector("band", 2, "",
                        "jonswap: the lowest and highest frequency as multiples of the peak's "
                        "(default [0.5, 3]); the components' heights are scaled so that "
                        "4 sqrt(m0) of their sum is `height`")
                     .optional());
  keys.push_back(integer("seed",
                         "jonswap: seed of the random phases (default 1; the same on "
                         "every machine: a 64-bit Mersenne twister)")
                     .at_least(0)
                     .optional());
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
          "speeds; a wave steeper than Miche's breaking limit is refused. spectrum = \"jonswap\": "
          "an irregular sea instead, each component with its own stroke.",
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
          "refused. spectrum = \"jonswap\": an irregular sea instead.",
          wave_keys({number("hinge_depth", "m",
                            "the hinge's depth l below the still surface (absent: the depth, a "
                            "flap hinged on the floor)")
                         .positive()
                         .optional()}))
          .as_list()
          .planar(),
  };
}

// The wave a block asks for; an fsi::Error at its key for no gravity, a wave that breaks, a hinge
// below the floor, a spectrum's key on a regular wave (each() then skips the block and the
// sensors naming it).
PaddleWave asked_wave(const SceneBuilder& builder, const View& block, bool flap) {
  const double gravity = std::hypot(builder.scene.gravity[0], builder.scene.gravity[1]);
  if (!(gravity > 0.0)) {
    throw Error(std::string(flap ? "a FlapWavemaker" : "a PistonWavemaker") +
                    " needs gravity (the waves' dispersion relation), and the scene has none",
                block.location().text(), "add Gravity { acceleration = [0, -9.81] }");
  }
  const auto text = [](double value) { return significant(value, 4); };
  const double depth = block.number("depth");
  const double ramp_time = block.number("ramp_periods") * block.number("period");
  double hinge_depth = 0.0;
  if (flap) {
    hinge_depth = block.has("hinge_depth") ? block.number("hinge_depth") : depth;
    if (hinge_depth > depth) {
      throw Error("the hinge " + text(hinge_depth) +
                      " m below the still surface is under the floor (depth " + text(depth) + " m)",
                  block.location("hinge_depth").text(),
                  "give a hinge_depth of at most the depth (or leave it out: a flap on the "
                  "floor)");
    }
  }
  const bool irregular = block.string("spectrum") == "jonswap";
  for (const char* key : {"gamma", "components", "band", "seed"}) {
    if (!irregular && block.has(key)) {
      throw Error("'" + std::string(key) + "' describes an irregular sea, and this wave is regular",
                  block.location(key).text(), "add spectrum = \"jonswap\", or leave the key out");
    }
  }
  PaddleWave wave;
  if (irregular) {
    SpectrumRequest request;
    request.significant_height = block.number("height");
    request.peak_period = block.number("period");
    if (block.has("gamma")) request.gamma = block.number("gamma");
    if (block.has("components")) request.count = static_cast<int>(block.integer("components"));
    if (block.has("seed")) request.seed = static_cast<std::uint64_t>(block.integer("seed"));
    if (block.has("band")) {
      const std::vector<double> band = block.vector("band");
      if (!(band[0] > 0.0 && band[0] < 1.0 && band[1] > 1.0)) {
        throw Error("the band [" + text(band[0]) + ", " + text(band[1]) +
                        "] does not run from below the peak frequency to above it",
                    block.location("band").text(),
                    "give [low, high] in multiples of the peak frequency with 0 < low < 1 < high, "
                    "e.g. [0.5, 3]");
      }
      request.band_low = band[0];
      request.band_high = band[1];
    }
    wave = irregular_wave(request, depth, hinge_depth, gravity, ramp_time);
  } else {
    wave = paddle_wave(block.number("height"), block.number("period"), depth, hinge_depth, gravity,
                       ramp_time);
  }
  if (wave.height > wave.breaking_height) {
    const std::string what = irregular ? "a sea of significant height " : "a wave ";
    throw Error(
        what + text(wave.height) + " m high and " + text(wave.wavelength) + " m long in water " +
            text(wave.depth) +
            " m deep is steeper than Miche's limit H = 0.142 tanh(kh) lambda = " +
            text(wave.breaking_height) + " m: it breaks at the paddle",
        block.location("height").text(),
        "lower the height below " + text(wave.breaking_height) + " m, or lengthen the period");
  }
  return wave;
}

void build_wavemaker(SceneBuilder& builder, const View& block, bool flap) {
  const PaddleWave wave = asked_wave(builder, block, flap);
  const mbd::BodyId body = builder.find_body(block, "body");
  if (builder.model.is_beam(body)) {
    throw Error("'" + block.string("body") + "' is an AncfBeam2D; a wavemaker's paddle is rigid",
                block.location("body").text(),
                "give the paddle as a RigidBody2D (a line for its Mesh)");
  }
  mbd::PrescribedMotionSpec spec;
  spec.name = name_of(block);
  spec.body = body;
  if (flap) {
    const double theta0 = builder.model.body(body).angle;
    spec.coordinate = mbd::Coordinate::Angle;
    spec.position = [theta0, wave](double t) { return theta0 + wave.flap_angle(t); };
    spec.rate = [wave](double t) { return wave.flap_angle_rate(t); };
  } else {
    const double x0 = builder.model.body(body).position.x();
    spec.coordinate = mbd::Coordinate::X;
    spec.position = [x0, wave](double t) { return x0 + wave.offset(t); };
    spec.rate = [wave](double t) { return wave.offset_rate(t); };
  }
  spec.check_times = prescribed_motion_check_times(builder.end_time);
  builder.add_joint(block, [&] { return builder.model.add_prescribed_motion(spec); },
                    {.rows = 1, .body = body, .kind = "prescribed motion"});
  builder.scene.wavemakers.push_back({block.location(), spec.name, block.string("body"), wave});
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
