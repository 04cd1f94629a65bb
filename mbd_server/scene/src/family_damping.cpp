// Damping zones: boxes where the fluid is slowed by a velocity drag during the coupled run, to
// absorb waves at a flume's end instead of reflecting them (docs/user-guide.md, "Absorbing
// waves: DampingZone"). The server turns each block into LIGGGHTS commands that fsi-client runs
// right after script 2 (damping_zone_commands).

#include <cmath>

#include "fsi/common/text.hpp"
#include "fsi/scene/scene.hpp"
#include "scene_builder.hpp"

namespace fsi::scene::detail {
namespace {

std::vector<BlockSpec> damping_blocks() {
  return {
      block_spec(
          "DampingZone",
          "A box where the fluid feels a velocity drag -rate s^2 m v during the coupled run (not "
          "the equilibration, which has its own settling drag): a sponge layer that absorbs "
          "waves at a flume's end. s grows from 0 at the box's side opposite `grows_toward` to 1 "
          "at that side, so that the drag starts smoothly (an abrupt drag reflects waves "
          "itself); uniform: s = 1 in the whole box. Zones may overlap (their drags add). The "
          "drag is an external force: the energy it removes leaves the fluid's books "
          "(docs/user-guide.md, \"Absorbing waves: DampingZone\").",
          {per_dimension(vector("lower", 2, "m", "the box's lower corner ([x, y]; 3D: [x, y, z])")),
           per_dimension(vector("upper", 2, "m", "the box's upper corner ([x, y]; 3D: [x, y, z])")),
           number("rate", "1/s",
                  "the drag rate lambda at s = 1 (a particle held there loses its velocity as "
                  "exp(-lambda t)); at most 1 / dt (the drag would reverse velocities); a wave "
                  "of period T is absorbed well by a zone a wavelength long with lambda of a few "
                  "2 pi / T (measured: the user guide)")
               .positive(),
           text("grows_toward",
                "the side where the drag is strongest: x+ (at upper x), x-, y+, y-, z+, z- (3D), "
                "or uniform")
               .one_of({"x+", "x-", "y+", "y-", "z+", "z-", "uniform"})})
          .as_list()
          .for_coupled_runs(),
  };
}

void build_damping_zones(SceneBuilder& builder) {
  builder.each("DampingZone", [&](const View& block) {
    DampingZone zone;
    zone.location = block.location();
    const auto lower = builder.dimension_vector(block, "lower", builder.dimension);
    const auto upper = builder.dimension_vector(block, "upper", builder.dimension);
    if (!lower || !upper) return;
    static constexpr const char* kAxes = "xyz";
    for (int k = 0; k < builder.dimension; ++k) {
      const auto i = static_cast<std::size_t>(k);
      zone.lower[i] = (*lower)[i];
      zone.upper[i] = (*upper)[i];
      if (!(zone.upper[i] > zone.lower[i])) {
        builder.problem(block.location("upper"),
                        std::string("the DampingZone's upper ") + kAxes[k] + " = " +
                            exact(zone.upper[i]) + " is not above its lower " + kAxes[k] + " = " +
                            exact(zone.lower[i]) + " (an empty box)",
                        "give lower the smaller and upper the larger coordinate of each axis");
        return;
      }
    }
    zone.rate = block.number("rate");
    const std::string& toward = block.string("grows_toward");
    if (toward != "uniform") {
      zone.axis = toward[0] - 'x';
      zone.toward_upper = toward[1] == '+';
      if (zone.axis >= builder.dimension) {
        builder.problem(block.location("grows_toward"),
                        "grows_toward = \"" + toward + "\" in a 2D scene (no z axis)",
                        "use x+, x-, y+, y- or uniform");
        return;
      }
    }
    const double step = builder.scene.solver.step_size;
    const auto rounded = [](double value) { return significant(value, 6); };
    if (step > 0.0 && zone.rate * step > 1.0) {
      builder.problem(block.location("rate"),
                      "the DampingZone's rate " + exact(zone.rate) +
                          " 1/s times the fluid's step " + rounded(step) + " s is " +
                          rounded(zone.rate * step) +
                          " > 1: the drag would reverse the particles' velocities every step",
                      "lower the rate to at most " + rounded(1.0 / step) +
                          " 1/s (a few 2 pi / T absorbs a wave of period T)");
      return;
    }
    builder.scene.damping_zones.push_back(zone);
  });
}

}  // namespace

ElementFamily damping_family() {
  return {"damping zones", damping_blocks, {build_damping_zones}};
}

}  // namespace fsi::scene::detail

namespace fsi::scene {

std::string damping_zone_commands(const std::vector<DampingZone>& zones, int dimension) {
  std::string out;
  static constexpr const char* kAxes = "xyz";
  for (std::size_t i = 0; i < zones.size(); ++i) {
    const DampingZone& zone = zones[i];
    const std::string id = "fsi_damping_" + std::to_string(i);
    auto bound = [&](int k, bool upper) {
      if (k >= dimension) return std::string(upper ? "1e10" : "-1e10");  // 2D: every z
      return fsi::exact(upper ? zone.upper[static_cast<std::size_t>(k)]
                              : zone.lower[static_cast<std::size_t>(k)]);
    };
    // s = (x - x0) / L toward upper x, (x1 - x) / L toward lower x: 0 at the inner side.
    std::string shape = "1.0";
    if (zone.axis >= 0) {
      const auto a = static_cast<std::size_t>(zone.axis);
      const std::string length = fsi::exact(zone.upper[a] - zone.lower[a]);
      const std::string coordinate(1, kAxes[zone.axis]);
      shape = zone.toward_upper
                  ? "((" + coordinate + "-(" + fsi::exact(zone.lower[a]) + "))/" + length + ")^2"
                  : "(((" + fsi::exact(zone.upper[a]) + ")-" + coordinate + ")/" + length + ")^2";
    }
    out += "# fsi-server: DampingZone " + zone.location.text() + ", a drag -rate s^2 m v\n";
    out += "region " + id + " block " + bound(0, false) + " " + bound(0, true) + " " +
           bound(1, false) + " " + bound(1, true) + " " + bound(2, false) + " " + bound(2, true) +
           " units box\n";
    out += "variable " + id + "_c atom -" + fsi::exact(zone.rate) + "*mass*" + shape + "\n";
    std::string forces;
    for (int k = 0; k < 3; ++k) {
      const std::string component(1, kAxes[k]);
      if (k < dimension) {
        out += "variable " + id + "_f" + component + " atom v_" + id + "_c*v" + component + "\n";
        forces += " v_" + id + "_f" + component;
      } else {
        forces += " 0.0";
      }
    }
    out += "fix " + id + " all addforce" + forces + " region " + id + "\n";
  }
  return out;
}

std::string script2_sent(const Scene& scene) {
  std::string text = scene.liggghts.script2_text;
  const std::string zones = damping_zone_commands(scene.damping_zones, scene.dimension);
  if (zones.empty()) return text;
  if (!text.empty() && text.back() != '\n') text += '\n';
  return text + zones;
}

}  // namespace fsi::scene
