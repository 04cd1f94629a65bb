// PistonWavemaker (family_wavemaker.cpp): linear piston-wavemaker theory, the paddle's motion,
// and the blocks refused.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "test_files.hpp"

namespace fsi::scene {
namespace {

TEST(PistonWave, LinearTheoryOfTheWaveFlapUsersFlume) {
  // T = 1.4 s, h = 0.4 m: the user computed k = 2.626 1/m and H/S = 1.028 by hand (Dean &
  // Dalrymple), and a stroke of 0.06 m made H = 0.0617 m 0.4 m from the paddle (docs/
  // validation.md, "Users' unseen cases").
  const PistonWave wave = piston_wave(0.0617, 1.4, 0.4, 9.81);
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
  const PistonWave deep = piston_wave(0.01, 0.5, 10.0, 9.81);
  EXPECT_NEAR(deep.height_per_stroke, 2.0, 1e-9);
  EXPECT_NEAR(deep.wavenumber, std::pow(2.0 * std::numbers::pi / 0.5, 2) / 9.81, 1e-9);
  const PistonWave shallow = piston_wave(0.001, 20.0, 0.05, 9.81);
  EXPECT_NEAR(shallow.height_per_stroke / (shallow.wavenumber * 0.05), 1.0, 1e-3);
  EXPECT_NEAR(shallow.phase_speed, std::sqrt(9.81 * 0.05), 1e-3);
}

TEST(PistonWave, ThePaddleRampsUpSmoothlyToItsStroke) {
  const PistonWave wave = piston_wave(0.0617, 1.4, 0.4, 9.81, 2.8);
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
  const PistonWave& wave = built.wavemakers[0].wave;
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

}  // namespace
}  // namespace fsi::scene
