// PistonWavemaker and FlapWavemaker (family_wavemaker.cpp): linear wavemaker theory, the
// paddle's motion, and the blocks refused.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fsi/mbd/integrator.hpp"
#include "test_files.hpp"

namespace fsi::scene {
namespace {

TEST(PistonWave, LinearTheoryOfTheWaveFlapUsersFlume) {
  // T = 1.4 s, h = 0.4 m: the user computed k = 2.626 1/m and H/S = 1.028 by hand (Dean &
  // Dalrymple), and a stroke of 0.06 m made H = 0.0617 m 0.4 m from the paddle (docs/
  // validation.md, "Users' unseen cases").
  const PaddleWave wave = piston_wave(0.0617, 1.4, 0.4, 9.81);
  const double omega = 2.0 * std::numbers::pi / 1.4;
  EXPECT_NEAR(wave.wavenumber * std::tanh(wave.wavenumber * 0.4), omega * omega / 9.81, 1e-12);
  EXPECT_NEAR(wave.wavenumber, 2.626, 5e-4);
  EXPECT_NEAR(wave.height_per_stroke, 1.028, 5e-4);
  EXPECT_NEAR(wave.stroke, 0.0600, 1e-4);
  EXPECT_NEAR(wave.phase_speed, omega / wave.wavenumber, 1e-12);
  EXPECT_GT(wave.group_speed, 0.5 * wave.phase_speed);
  EXPECT_LT(wave.group_speed, wave.phase_speed);
  // The limits of the transfer function: deep water H/S -> 2 (and k -> omega^2/g), shallow
  // water H/S -> kh.
  const PaddleWave deep = piston_wave(0.01, 0.5, 10.0, 9.81);
  EXPECT_NEAR(deep.height_per_stroke, 2.0, 1e-9);
  EXPECT_NEAR(deep.wavenumber, std::pow(2.0 * std::numbers::pi / 0.5, 2) / 9.81, 1e-9);
  const PaddleWave shallow = piston_wave(0.001, 20.0, 0.05, 9.81);
  EXPECT_NEAR(shallow.height_per_stroke / (shallow.wavenumber * 0.05), 1.0, 1e-3);
  EXPECT_NEAR(shallow.phase_speed, std::sqrt(9.81 * 0.05), 1e-3);
  // kh = 1610: sinh(2kh) overflows a double; the transfer function must not.
  const PaddleWave deeper = piston_wave(0.01, 0.5, 100.0, 9.81);
  EXPECT_NEAR(deeper.height_per_stroke, 2.0, 1e-9);
  EXPECT_NEAR(deeper.group_speed, 0.5 * deeper.phase_speed, 1e-9);
}

TEST(PistonWave, ThePaddleRampsUpSmoothlyToItsStroke) {
  const PaddleWave wave = piston_wave(0.0617, 1.4, 0.4, 9.81, 2.8);
  EXPECT_EQ(wave.offset(0.0), 0.0);
  EXPECT_EQ(wave.offset_rate(0.0), 0.0);
  // After the ramp: S/2 sin(omega t); at a quarter period past 2.8 s the crest of the stroke.
  EXPECT_NEAR(wave.offset(2.8 + 0.35), 0.5 * wave.stroke, 1e-12);
  double largest = 0.0;
  for (double t = 0.0; t < 10.0; t += 1e-3) {
    largest = std::max(largest, std::abs(wave.offset(t)));
    const double difference = (wave.offset(t + 1e-6) - wave.offset(t - 1e-6)) / 2e-6;
    ASSERT_NEAR(wave.offset_rate(t), difference, 1e-6) << "t = " << t;
  }
  EXPECT_NEAR(largest, 0.5 * wave.stroke, 1e-6);
}

// The transfer function of a flap hinged at depth l, from the profile of the water it moves,
// X(z)/(S/2) = 1 - z/l above the hinge and 0 below, integrated here by Simpson's rule instead of
// in closed form: H/S = 4 k sinh(kh) / (sinh 2kh + 2kh) times the integral of X(z)/(S/2)
// cosh k(h - z) over 0 <= z <= h (Dean & Dalrymple 1991, §6.2).
double flap_height_per_stroke_by_quadrature(double k, double h, double l) {
  const int n = 20000;  // even
  const double dz = h / n;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double z = i * dz;
    const double profile = z < l ? 1.0 - z / l : 0.0;
    const double weight = (i == 0 || i == n) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    sum += weight * profile * std::cosh(k * (h - z));
  }
  const double integral = sum * dz / 3.0;
  return 4.0 * k * std::sinh(k * h) * integral / (std::sinh(2.0 * k * h) + 2.0 * k * h);
}

TEST(FlapWave, LinearTheoryOfAFlapOnTheFloorAndAboveIt) {
  // On the floor (l = h): Dean & Dalrymple's closed form 4 (sinh kh / kh)(kh sinh kh - cosh kh
  // + 1) / (sinh 2kh + 2kh); T = 1.4 s, h = 0.4 m: kh = 1.0504, H/S = 0.5563.
  const PaddleWave floor = flap_wave(0.0617, 1.4, 0.4, 0.4, 9.81);
  const double kh = floor.wavenumber * 0.4;
  EXPECT_NEAR(floor.wavenumber, 2.626, 5e-4);  // the dispersion relation, as the piston's
  const double closed = 4.0 * (std::sinh(kh) / kh) * (kh * std::sinh(kh) - std::cosh(kh) + 1.0) /
                        (std::sinh(2.0 * kh) + 2.0 * kh);
  EXPECT_NEAR(floor.height_per_stroke, closed, 1e-12);
  EXPECT_NEAR(floor.height_per_stroke, 0.5563, 1e-4);
  EXPECT_NEAR(floor.stroke, 0.0617 / closed, 1e-12);
  EXPECT_TRUE(floor.flap());
  EXPECT_FALSE(piston_wave(0.0617, 1.4, 0.4, 9.81).flap());
  // Hinged above the floor: against the quadrature of the moved water's profile.
  for (const double l : {0.1, 0.25, 0.4}) {
    const PaddleWave wave = flap_wave(0.05, 1.4, 0.4, l, 9.81);
    EXPECT_NEAR(wave.height_per_stroke,
                flap_height_per_stroke_by_quadrature(wave.wavenumber, 0.4, l), 1e-9)
        << "l = " << l;
  }
  // The limits: shallow water H/S -> kh/2 (half the piston's), deep water -> 2 (the flap moves
  // the top of the water, where the wave lives, like a piston).
  const PaddleWave shallow = flap_wave(0.001, 20.0, 0.05, 0.05, 9.81);
  EXPECT_NEAR(shallow.height_per_stroke / (0.5 * shallow.wavenumber * 0.05), 1.0, 1e-3);
  const PaddleWave deep = flap_wave(0.01, 0.5, 100.0, 100.0, 9.81);
  EXPECT_NEAR(deep.height_per_stroke, 2.0, 2.0 / (deep.wavenumber * 100.0) + 1e-9);
}

TEST(FlapWave, TheAngleMovesTheFlapsSurfacePointByTheOffset) {
  const PaddleWave wave = flap_wave(0.0617, 1.4, 0.4, 0.3, 9.81, 2.8);
  EXPECT_EQ(wave.flap_angle(0.0), 0.0);
  for (double t = 0.0; t < 8.0; t += 1e-3) {
    // The flap's line through the hinge crosses the still surface, l above it, at l tan(-angle).
    ASSERT_NEAR(0.3 * std::tan(-wave.flap_angle(t)), wave.offset(t), 1e-14) << "t = " << t;
    const double difference = (wave.flap_angle(t + 1e-6) - wave.flap_angle(t - 1e-6)) / 2e-6;
    ASSERT_NEAR(wave.flap_angle_rate(t), difference, 1e-6) << "t = " << t;
  }
}

// JONSWAP's density written here from DNV-RP-C205 eq. (3.5.5) with Hs = 1, independently of the
// code under test.
double jonswap_density(double omega, double peak, double gamma) {
  const double sigma = omega <= peak ? 0.07 : 0.09;
  const double alpha =
      std::exp(-(omega - peak) * (omega - peak) / (2 * sigma * sigma * peak * peak));
  const double pm = 5.0 / 16.0 * std::pow(peak, 4) / std::pow(omega, 5) *
                    std::exp(-5.0 / 4.0 * std::pow(omega / peak, -4));
  return (1 - 0.287 * std::log(gamma)) * pm * std::pow(gamma, alpha);
}

TEST(IrregularWave, TheComponentsFollowTheSpectrumAndSumToItsSignificantHeight) {
  for (const double gamma : {1.0, 3.3}) {
    SpectrumRequest request;
    request.significant_height = 0.05;
    request.peak_period = 1.4;
    request.gamma = gamma;
    const PaddleWave sea = irregular_wave(request, 0.4, 0.0, 9.81, 2.8);
    ASSERT_EQ(sea.components.size(), 64u);
    const double peak = 2 * std::numbers::pi / 1.4, width = 2.5 * peak / 64;
    EXPECT_NEAR(sea.repeat_period, 2 * std::numbers::pi / width, 1e-9);
    double m0 = 0.0;
    for (std::size_t i = 0; i < sea.components.size(); ++i) {
      const WaveComponent& c = sea.components[i];
      EXPECT_NEAR(c.omega, (13 + i) * width, 1e-12);  // 0.5 peak / width = 12.8: bands from 13
      EXPECT_GE(c.phase, 0.0);
      EXPECT_LT(c.phase, 2 * std::numbers::pi);
      m0 += c.height * c.height / 8;
      // Each component's stroke is the regular wave's of its height and frequency.
      const PaddleWave alone = piston_wave(c.height, 2 * std::numbers::pi / c.omega, 0.4, 9.81);
      EXPECT_NEAR(c.half_stroke, 0.5 * alone.stroke, 1e-15);
      // The discrete amplitude 2 sqrt(2 S d omega), S for Hs = 0.05: the scale that makes the
      // sum's 4 sqrt(m0) exact stays within what the band's tails and A_gamma leave out.
      const double expected =
          2 * std::sqrt(2 * 0.05 * 0.05 * jonswap_density(c.omega, peak, gamma) * width);
      EXPECT_NEAR(c.height / expected, 1.0, gamma == 1.0 ? 0.01 : 0.05) << "gamma " << gamma;
    }
    EXPECT_NEAR(4 * std::sqrt(m0), 0.05, 1e-12);
  }
}

TEST(IrregularWave, TheSeaRepeatsAndIsTheSameForTheSameSeed) {
  SpectrumRequest request;
  request.significant_height = 0.05;
  request.peak_period = 1.4;
  const PaddleWave sea = irregular_wave(request, 0.4, 0.4, 9.81, 2.8);  // a flap on the floor
  for (double t = 3.0; t < 10.0; t += 0.37) {
    ASSERT_NEAR(sea.offset(t + sea.repeat_period), sea.offset(t), 1e-12) << t;
    const double difference = (sea.offset(t + 1e-6) - sea.offset(t - 1e-6)) / 2e-6;
    ASSERT_NEAR(sea.offset_rate(t), difference, 1e-6) << t;
  }
  EXPECT_EQ(sea.offset(0.0), 0.0);
  EXPECT_EQ(sea.offset_rate(0.0), 0.0);
  // A flap's components take the flap's transfer function.
  const WaveComponent& c = sea.components[10];
  EXPECT_NEAR(c.half_stroke,
              0.5 * flap_wave(c.height, 2 * std::numbers::pi / c.omega, 0.4, 0.4, 9.81).stroke,
              1e-15);
  EXPECT_GT(sea.largest_offset, 0.0);
  const PaddleWave again = irregular_wave(request, 0.4, 0.4, 9.81, 2.8);
  request.seed = 2;
  const PaddleWave other = irregular_wave(request, 0.4, 0.4, 9.81, 2.8);
  int differ = 0;
  for (std::size_t i = 0; i < sea.components.size(); ++i) {
    EXPECT_EQ(again.components[i].phase, sea.components[i].phase);
    differ += other.components[i].phase != sea.components[i].phase;
  }
  EXPECT_EQ(differ, 64);
}

class Wavemakers : public testing::FolderPerTest {
 protected:
  std::string scene(const std::string& wavemaker,
                    const std::string& gravity = "Gravity { acceleration = [0, -9.81] }\n") {
    return "scene_language = 1\n"
           "SolverOptions { end_time = 4; Timeint { step_size = 1e-3 } }\n" +
           gravity +
           "RigidBody2D { name = \"paddle\"; mass = 1; inertia = 0.05; position = [0.1, 0.3]\n"
           "  Mesh { points = [[0, -0.3], [0, 0.3]] } }\n"
           "CoordinateConstraint { body = \"paddle\"; coordinate = \"y\" }\n"
           "CoordinateConstraint { body = \"paddle\"; coordinate = \"angle\" }\n" +
           wavemaker +
           "Sensor { name = \"drive\"; type = \"joint_force\"; joint = \"stroke\"; component = "
           "\"x\" }\n";
  }
};

TEST_F(Wavemakers, TheBlockDrivesItsPaddleAndNamesItsWave) {
  Scene built;
  ASSERT_EQ(mbd_only_outcome("w.scene",
                             scene("PistonWavemaker { name = \"stroke\"; body = \"paddle\"; height "
                                   "= 0.0617; period = 1.4; depth = 0.4 }\n"),
                             &built),
            "(accepted)");
  ASSERT_EQ(built.wavemakers.size(), 1u);
  const PaddleWave& wave = built.wavemakers[0].wave;
  EXPECT_NEAR(wave.stroke, 0.0600, 1e-4);
  EXPECT_DOUBLE_EQ(wave.ramp_time, 2.8);  // the default two periods
  EXPECT_EQ(built.wavemakers[0].location.line, 8);
  // Two holding constraints and the drive: 3 rows, the drive's named for its sensor.
  EXPECT_EQ(built.sensors.size(), 1u);
}

TEST_F(Wavemakers, WavesThatCannotBeMadeAreRefused) {
  const std::string breaking =
      mbd_only_outcome("b.scene", scene("PistonWavemaker { body = \"paddle\"; height = 0.3; "
                                        "period = 1.4; depth = 0.4 }\n"));
  // T = 1.4 s, h = 0.4 m: lambda = 2.393 m, the limit 0.142 tanh(1.05) lambda = 0.2657 m.
  EXPECT_NE(breaking.find("a wave 0.3 m high and 2.393 m long in water 0.4 m deep is steeper than "
                          "Miche's limit H = 0.142 tanh(kh) lambda = 0.2657 m"),
            std::string::npos)
      << breaking;
  EXPECT_NE(breaking.find("it breaks at the paddle"), std::string::npos) << breaking;
  const std::string weightless = mbd_only_outcome(
      "g.scene",
      scene("PistonWavemaker { body = \"paddle\"; height = 0.05; period = 1.4; depth = 0.4 }\n",
            ""));
  EXPECT_NE(weightless.find("a PistonWavemaker needs gravity"), std::string::npos) << weightless;
  const std::string unknown = mbd_only_outcome(
      "u.scene",
      scene("PistonWavemaker { body = \"padle\"; height = 0.05; period = 1.4; depth = 0.4 }\n"));
  EXPECT_NE(unknown.find("padle"), std::string::npos) << unknown;
}

// A flap on the floor of water 0.4 m deep, pinned at its foot: run by the scene's integrator, the
// flap's line crosses the still surface where the theory's stroke puts it.
TEST_F(Wavemakers, TheFlapTurnsAboutItsHingeSoThatTheSurfaceMovesByTheStroke) {
  const std::string text =
      "scene_language = 1\n"
      "SolverOptions { end_time = 3.15; Timeint { step_size = 1e-3 } }\n"
      "Gravity { acceleration = [0, -9.81] }\n"
      "RigidBody2D { name = \"flap\"; mass = 2; inertia = 0.06; position = [0.1, 0.3]\n"
      "  Mesh { points = [[0, -0.3], [0, 0.3]] } }\n"
      "RevoluteJoint { name = \"hinge\"; body_a = \"flap\"; point_a = [0, -0.3]; point_b = "
      "[0.1, 0] }\n"
      "FlapWavemaker { name = \"swing\"; body = \"flap\"; height = 0.0617; period = 1.4; "
      "depth = 0.4 }\n"
      "Sensor { name = \"drive\"; type = \"joint_force\"; joint = \"swing\"; component = "
      "\"torque\" }\n";
  const Scene scene = build_scene(write("f.scene", text), {}, SceneMode::MbdOnly);
  ASSERT_EQ(scene.wavemakers.size(), 1u);
  const PaddleWave& wave = scene.wavemakers[0].wave;
  EXPECT_DOUBLE_EQ(wave.hinge_depth, 0.4);  // absent: on the floor
  EXPECT_NEAR(wave.stroke, 0.0617 / 0.5563, 1e-4);
  mbd::RadauIIA integrator(scene.solver.integrator_options());
  mbd::State state = scene.model.initial_state();
  const auto steps = static_cast<long>(std::lround(3.15 / scene.solver.step_size));
  for (long n = 0; n < steps; ++n)
    integrator.step(scene.model, state, scene.solver.step_size);
  // t = 2.8 s + a quarter period: the full half stroke. The foot stays at the hinge.
  const double angle = state.q(2);
  const double x = state.q(0), y = state.q(1);
  EXPECT_NEAR(x + 0.3 * std::sin(angle), 0.1, 1e-9);  // the foot, [0, -0.3] in the body
  EXPECT_NEAR(y - 0.3 * std::cos(angle), 0.0, 1e-9);
  EXPECT_NEAR(0.4 * std::tan(-angle), 0.5 * wave.stroke, 1e-9);
}

TEST_F(Wavemakers, AFlapHingedBelowTheFloorIsRefused) {
  const std::string below = mbd_only_outcome(
      "h.scene", scene("FlapWavemaker { body = \"paddle\"; height = 0.05; period = 1.4; depth "
                       "= 0.4; hinge_depth = 0.5 }\n"));
  EXPECT_NE(below.find("the hinge 0.5 m below the still surface is under the floor (depth 0.4 m)"),
            std::string::npos)
      << below;
  EXPECT_NE(below.find("give a hinge_depth of at most the depth"), std::string::npos) << below;
  const std::string breaking =
      mbd_only_outcome("b.scene", scene("FlapWavemaker { body = \"paddle\"; height = 0.3; "
                                        "period = 1.4; depth = 0.4 }\n"));
  EXPECT_NE(breaking.find("steeper than Miche's limit"), std::string::npos) << breaking;
}

TEST_F(Wavemakers, AnIrregularSeaIsASpectrumsComponentsAndItsKeysAreChecked) {
  Scene built;
  ASSERT_EQ(mbd_only_outcome("j.scene",
                             scene("PistonWavemaker { name = \"stroke\"; body = \"paddle\"; height "
                                   "= 0.05; period = 1.4; depth = 0.4; spectrum = \"jonswap\"; "
                                   "components = 32; gamma = 2; band = [0.6, 2.5]; seed = 7 }\n"),
                             &built),
            "(accepted)");
  ASSERT_EQ(built.wavemakers.size(), 1u);
  const PaddleWave& sea = built.wavemakers[0].wave;
  EXPECT_EQ(sea.spectrum, "jonswap");
  EXPECT_EQ(sea.components.size(), 32u);
  EXPECT_DOUBLE_EQ(sea.peak_enhancement, 2.0);
  const double peak = 2 * std::numbers::pi / 1.4;
  // 0.6 / (1.9 / 32) = 10.1: the first band's middle nearest 11 widths.
  EXPECT_NEAR(sea.components.front().omega, 11 * peak * 1.9 / 32, 1e-12);
  const std::string regular = mbd_only_outcome(
      "r.scene", scene("PistonWavemaker { name = \"stroke\"; body = \"paddle\"; height = 0.05; "
                       "period = 1.4; depth = 0.4; gamma = 2 }\n"));
  EXPECT_NE(regular.find("'gamma' describes an irregular sea, and this wave is regular"),
            std::string::npos)
      << regular;
  // The refused wavemaker skips the sensor naming it instead of a second problem about it.
  EXPECT_EQ(regular.find("no joint named 'stroke'"), std::string::npos) << regular;
  const std::string band = mbd_only_outcome(
      "b.scene", scene("PistonWavemaker { name = \"stroke\"; body = \"paddle\"; height = 0.05; "
                       "period = 1.4; depth = 0.4; spectrum = \"jonswap\"; band = [1.2, 3] }\n"));
  EXPECT_NE(band.find("the band [1.2, 3] does not run from below the peak frequency to above it"),
            std::string::npos)
      << band;
}

}  // namespace
}  // namespace fsi::scene
