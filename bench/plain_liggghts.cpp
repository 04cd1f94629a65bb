// The baseline of the coupling benchmark: the scene's fluid in plain LIGGGHTS, driven exactly
// like fsi-client does (same variables, scripts, particles, equilibration, time step), but with
// the structure replaced by LIGGGHTS' own `fix wall/region/sph` walls around a block region, and
// the measured steps done in one `run M`. The decomposition is fsi-client's at its set-up (the
// grid from the fluid's extent unless script 1 names one, cuts balanced; `--balance off`:
// LIGGGHTS' even cuts), not re-balanced during the run. Prints one JSON line with the loop wall
// time.
//
//   mpirun -np N bench_plain_liggghts SCENE --steps M (--region XLO XHI YLO YHI [ZLO ZHI] |
//       --walls none) [--balance off]
//       [--cutoff R] [--strength D] [--per-step] [--command LINE]... [--set KEY=EXPR]...
#include <mpi.h>
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <regex>
#include <string>

#include "decomposition.hpp"
#include "fluid_decomposition.hpp"
#include "fsi/common/error.hpp"
#include "fsi/scene/scene.hpp"
#include "liggghts_driver.hpp"

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  CLI::App app{"Plain-LIGGGHTS baseline of a scene (wall/region/sph walls instead of fix fsi/sph)"};
  std::string scene_file;
  long steps = 1000;
  std::vector<double> region;
  std::vector<std::string> overrides;
  app.add_option("scene", scene_file)->required();
  app.add_option("--steps", steps)->required();
  app.add_option("--region", region, "block XLO XHI YLO YHI [ZLO ZHI] of the walls (3D: all six)")
      ->expected(4, 6);
  app.add_option("--set", overrides);
  std::string balance = "on";
  app.add_option("--balance", balance)->check(CLI::IsMember({"on", "off"}));
  bool per_step = false;
  app.add_flag("--per-step", per_step, "one `run 1 pre no post no` per step, as fsi-client does");
  std::vector<std::string> extra_commands;
  app.add_option("--command", extra_commands, "LIGGGHTS command after script 2 (repeatable)");
  std::string cutoff = "${SPH_wall_cutoff}";
  app.add_option("--cutoff", cutoff, "cut-off of the walls (default: the scene's SPH_wall_cutoff)");
  std::string walls_kind = "region";
  app.add_option("--walls", walls_kind,
                 "region: wall/region/sph walls around --region; none: no walls at all (the "
                 "cheapest baseline, for scenes whose particles start closer to the walls than "
                 "wall/region/sph holds, over a measured interval too short for the fluid to "
                 "spread)")
      ->check(CLI::IsMember({"region", "none"}));
  double strength = 5.0;
  app.add_option("--strength", strength,
                 "wall/region/sph's prefactor D of the repulsion (default 5)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int status = rank == 0 ? app.exit(error) : 2;
    MPI_Finalize();
    return status;
  }
  try {
    std::vector<fsi::scene::Override> parsed;
    for (const auto& item : overrides)
      parsed.push_back(fsi::scene::parse_override(item));
    const fsi::scene::Scene scene = fsi::scene::build_scene(scene_file, parsed);
    auto boundary = std::make_shared<fsi::contact::CouplingBoundary>();
    fsi::client::LiggghtsDriver driver(MPI_COMM_WORLD, {}, boundary);
    driver.define_variables(scene.liggghts.variables);
    // The structure becomes LIGGGHTS walls: same cut-off as our fix, LIGGGHTS' own force law.
    if (walls_kind == "region" && region.size() != (scene.dimension == 3 ? 6u : 4u)) {
      throw fsi::Error("--region needs " + std::string(scene.dimension == 3 ? "six" : "four") +
                           " numbers for a " + std::to_string(scene.dimension) + "D scene",
                       "command line", "give XLO XHI YLO YHI (and ZLO ZHI in 3D)");
    }
    const double z_low = region.size() == 6 ? region[4] : -1.0;
    const double z_high = region.size() == 6 ? region[5] : 1.0;
    char walls[512] = "";
    if (walls_kind == "region")
      std::snprintf(walls, sizeof walls,
                    "region fsi_bench_tank block %.17g %.17g %.17g %.17g %.17g %.17g units box\n"
                    "fix fsi_bench_walls all wall/region/sph fsi_bench_tank %s %.17g",
                    region[0], region[1], region[2], region[3], z_low, z_high, cutoff.c_str(),
                    strength);
    const std::string script1 = std::regex_replace(
        scene.liggghts.script1_text,
        std::regex(R"(fix\s+\S+\s+\S+\s+fsi/sph(?:[^\n&]*&[ \t]*\n)*[^\n]*)"), walls);
    fsi::client::ParticleBlock particles;
    particles.dimension = scene.dimension;
    particles.mass = scene.fluid.mass;
    particles.density = scene.fluid.density;
    particles.atom_type = scene.fluid.atom_type;
    particles.positions = scene.fluid.positions;
    particles.velocities = scene.fluid.velocities;
    int ranks = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    if (balance == "on" && ranks > 1 && !particles.positions.empty()) {
      driver.set_automatic_grid(fsi::client::choose_processor_grid(
          ranks, scene.dimension,
          fsi::client::positions_extent(particles.positions, scene.dimension)));
    }
    driver.run_script(scene.liggghts.script1_name + " (walls: wall/region/sph)", script1,
                      [&] { driver.insert_particles(particles); });
    if (balance == "on" && ranks > 1) {
      fsi::client::apply_cuts(driver.lammps(), fsi::client::balanced_cuts_of_particles(
                                                   driver.lammps(), MPI_COMM_WORLD));
      fsi::client::migrate_particles(driver.lammps());
    }
    driver.set_time_step(scene.solver.step_size);
    driver.run_with_setup(0);
    if (scene.liggghts.equilibration_steps > 0)
      driver.run_with_setup(scene.liggghts.equilibration_steps);
    // Script 2 as fsi-server sends it (with the scene's damping zones).
    driver.run_script(scene.liggghts.script2_name, fsi::scene::script2_sent(scene));
    driver.run_with_setup(0);
    for (const std::string& line : extra_commands)
      driver.command(line);
    if (!extra_commands.empty()) driver.run_with_setup(0);
    MPI_Barrier(MPI_COMM_WORLD);
    const auto start = std::chrono::steady_clock::now();
    if (per_step) {
      // As fsi-client steps the coupled phase: one `run 1 pre no post no` per step.
      for (long k = 0; k < steps; ++k)
        driver.step();
    } else {
      driver.run_with_setup(static_cast<std::uint64_t>(steps));
    }
    MPI_Barrier(MPI_COMM_WORLD);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (rank == 0) {
      std::printf("{\"particles\": %llu, \"steps\": %ld, \"ranks\": %d, \"seconds_loop\": %.6f}\n",
                  static_cast<unsigned long long>(driver.particle_count()), steps, ranks, seconds);
    }
  } catch (const std::exception& failure) {
    std::fprintf(stderr, "bench_plain_liggghts (rank %d): %s\n", rank, failure.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Finalize();
  return 0;
}
