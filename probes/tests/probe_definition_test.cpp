// Probe definitions and their columns of sensors.csv.

#include <gtest/gtest.h>

#include "fsi/common/error.hpp"
#include "fsi/probes/evaluation.hpp"
#include "fsi/probes/probe.hpp"

namespace fsi::probes {
namespace {

std::vector<std::string> names_of(const std::vector<Column>& columns) {
  std::vector<std::string> names;
  for (const Column& column : columns)
    names.push_back(column.name + " [" + column.unit + "]");
  return names;
}

TEST(ProbeColumns, EachKindNamesItsColumnsWithUnits) {
  EXPECT_EQ(names_of(columns(fluid_energy_probe("water", {}), 2)),
            (std::vector<std::string>{"water_kinetic [J/m]", "water_potential [J/m]"}));
  EXPECT_EQ(names_of(columns(fluid_energy_probe("water", {}), 3)),
            (std::vector<std::string>{"water_kinetic [J]", "water_potential [J]"}));
  EXPECT_EQ(names_of(columns(point_probe("p1", {}), 2)),
            (std::vector<std::string>{"p1_vx [m/s]", "p1_vy [m/s]", "p1_pressure [Pa]",
                                      "p1_particles [-]", "p1_wet [-]"}));
  EXPECT_EQ(columns(point_probe("p1", {}), 3).size(), 6u);
  EXPECT_EQ(names_of(columns(free_surface_probe("level", {}, 0.1, 50), 2)),
            (std::vector<std::string>{"level_elevation [m]", "level_wet [-]"}));
  EXPECT_EQ(names_of(columns(flux_probe("q", {{0, 0, 0}, {0, 1, 0}}, 10), 2)),
            (std::vector<std::string>{"q_flux [m^2/s]"}));
  EXPECT_EQ(names_of(columns(flux_probe("q", {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}}, 10), 3)),
            (std::vector<std::string>{"q_flux [m^3/s]"}));
  EXPECT_EQ(names_of(columns(front_probe("surge", 0, 1, 3), 2)),
            (std::vector<std::string>{"surge_position [m]", "surge_wet [-]"}));
}

TEST(ProbeColumns, ProbeSetListsEveryColumnInOrder) {
  const ProbeSet set({point_probe("a", {}), fluid_energy_probe("b", {})},
                     {2, {0, -9.81, 0}, 0.001});
  EXPECT_EQ(set.column_count(), 7u);
  EXPECT_EQ(set.columns()[5].name, "b_kinetic");
}

TEST(ProbeDefinitionCheck, NamesWhatDoesNotFit) {
  EXPECT_EQ(definition_problem(point_probe("p", {}), 2), "");
  ProbeDefinition short_point = point_probe("p", {});
  short_point.parameters.pop_back();
  EXPECT_EQ(definition_problem(short_point, 2), "a point probe has 3 parameters, 'p' has 2");
  EXPECT_NE(definition_problem(free_surface_probe("s", {}, 0.0, 10), 2).find("length > 0"),
            std::string::npos);
  EXPECT_NE(definition_problem(free_surface_probe("s", {}, 1.0, 1), 2).find("2 to 100000 samples"),
            std::string::npos);
  EXPECT_NE(definition_problem(front_probe("f", 2, 1, 3), 2).find("axis outside 0 to 1"),
            std::string::npos);
  EXPECT_EQ(definition_problem(front_probe("f", 2, 1, 3), 3), "");
  EXPECT_NE(definition_problem(front_probe("f", 0, 0, 3), 2).find("direction"), std::string::npos);
  EXPECT_EQ(definition_problem(flux_probe("q", {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}}, 10), 2),
            "flux probe 'q' needs a segment of 2 points");
  EXPECT_EQ(definition_problem(flux_probe("q", {{0, 0, 0}, {0, 1, 0}, {0, 2, 0}}, 10), 3),
            "flux probe 'q' has no area (its points are in line)");
  EXPECT_NE(
      definition_problem(flux_probe("q", {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0.1}}, 10), 3)
          .find("flux probe 'q' is not planar"),
      std::string::npos);
  EXPECT_EQ(definition_problem(flux_probe("q", {{0, 0, 0}, {0, 0, 0}}, 10), 2),
            "flux probe 'q' has no extent");
  ProbeDefinition unknown{static_cast<ProbeKind>(99), "u", {}};
  EXPECT_EQ(definition_problem(unknown, 2), "probe 'u' is of unknown kind 99");
  EXPECT_FALSE(is_known_kind(99));
  EXPECT_TRUE(is_known_kind(static_cast<std::uint32_t>(ProbeKind::Front)));
}

TEST(ProbeDefinitionCheck, ProbeSetRefusesABadDefinitionAndAFrontWithoutSpacing) {
  EXPECT_THROW(ProbeSet({free_surface_probe("s", {}, -1.0, 10)}, {2, {}, 0.001}), Error);
  EXPECT_THROW(ProbeSet({front_probe("f", 0, 1, 3)}, {2, {}, 0.0}), Error);
}

// Placement by a body's rigid motion (protocol 1.4): points move, directions turn, the rest stays.
TEST(ProbePlacement, MovesPointsTurnsDirectionsAndKeepsTheRest) {
  RigidPlacement quarter_turn;  // 90 degrees about z, then 1 m along x
  quarter_turn.rotation = {0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0};
  quarter_turn.translation = {1.0, 0.0, 0.0};
  EXPECT_EQ(placed(point_probe("p", {2.0, 3.0, 0.0}), quarter_turn).parameters,
            (std::vector<double>{-2.0, 2.0, 0.0}));
  EXPECT_EQ(placed(free_surface_probe("s", {2.0, 0.0, 0.0}, 0.5, 20), quarter_turn).parameters,
            (std::vector<double>{1.0, 2.0, 0.0, 0.5, 20.0}));
  EXPECT_EQ(placed(flux_probe("q", {{0, 0, 0}, {0, 1, 0}}, 10), quarter_turn).parameters,
            (std::vector<double>{2.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 10.0}));
  const ProbeDefinition wall =
      wall_pressure_probe("w", {0.0, 2.0, 0.0}, 0.1, {1.0, 0.0, 0.0}, {{4, 9}});
  EXPECT_EQ(placed(wall, quarter_turn).parameters,
            (std::vector<double>{-1.0, 0.0, 0.0, 0.1, 0.0, 1.0, 0.0, 1.0, 4.0, 9.0}));
  EXPECT_TRUE(can_move(ProbeKind::Point));
  EXPECT_FALSE(can_move(ProbeKind::Front));
  EXPECT_FALSE(can_move(ProbeKind::FluidEnergy));
  EXPECT_THROW(placed(front_probe("f", 0, 1, 3), quarter_turn), Error);
  const RigidPlacement identity;
  EXPECT_EQ(placed(wall, identity), wall);
}

}  // namespace
}  // namespace fsi::probes
