#pragma once
// `fix fsi/sph` inside Debian's LIGGGHTS 3.8 (ARCHITECTURE.md §3). LIGGGHTS' style tables are
// compiled in, so the fix is not found by name: the client recognises the script line and calls
// add_fix_fsi_sph(), which constructs the fix and appends it to LIGGGHTS' fix list the way
// Modify::add_fix does.
//
// The client and the fix share a CouplingBoundary: the client writes vertex positions and
// velocities into it before each step, the fix writes this rank's vertex forces and diagnostics.

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "fsi/contact/wall_contact.hpp"
#include "fsi/contact/wall_contact_3d.hpp"

namespace LAMMPS_NS {
class LAMMPS;
}

namespace fsi::contact {

struct CouplingBoundary {
  int dimension = 2;      // 2: segments in `mesh`; 3: triangles in `mesh3d`
  BoundaryMesh2D mesh;    // all vertices, dynamic ones first
  BoundaryMesh3D mesh3d;  // likewise, in 3D
  std::size_t dynamic_vertex_count = 0;
  double refinement_resolution = 0.0;
  int refinement_option = 1;  // thesis Table 5.1; 3D only (2D always refines every step)
  ForceLaw law;               // set when the fix is created from the script

  // The vertex arrays of the active mesh (dimension values per vertex).
  std::vector<double>& positions() { return dimension == 3 ? mesh3d.positions : mesh.positions; }
  std::vector<double>& velocities() { return dimension == 3 ? mesh3d.velocities : mesh.velocities; }
  // Sets the mesh from the server's arrays; throws std::invalid_argument naming the problem.
  void assign(int mesh_dimension, std::vector<double> vertex_positions,
              std::vector<double> vertex_velocities, std::vector<std::uint32_t> elements);

  // A rank's share of the whole mesh (fsi-client's boundary_distribution.hpp): `mesh`/`mesh3d`
  // then hold only the elements within reach of this rank's particles. `coverage` is the box the
  // rank's particles must stay in for that to hold: the fix stops with an error naming the
  // particle when one is outside it. `share_pending`: the client has not handed out the shares
  // yet, and the fix refuses to evaluate. `share_generation` counts the shares handed out;
  // `pre_refinement` holds the share's levels of a mesh pre-refined whole (3D options 2, 3).
  // `drawn_bounds`: two corners of the whole mesh's bounding box as drawn, for the periodic-box
  // check (empty: the mesh's own vertices).
  struct Coverage {
    bool active = false;
    std::array<double, 3> low{}, high{};
  };
  Coverage coverage;
  bool share_pending = false;
  std::uint64_t share_generation = 0;
  std::vector<std::uint8_t> pre_refinement;
  std::vector<double> drawn_bounds;

  // Results of the latest evaluation on this rank (not yet summed over ranks).
  std::vector<double> vertex_forces;
  // The force at every sampling point, recorded while `samples.enabled` (wall-pressure probes).
  WallSampleRecord samples;
  ContactDiagnostics diagnostics;
  std::uint64_t evaluations = 0;
  double seconds_in_fix = 0.0;  // accumulated on this rank
  // Sampling points over this rank's evaluations: all of them, and those generated (within
  // reach of a particle of this rank; the rank's share of the boundary work).
  std::uint64_t sampling_points = 0;
  std::uint64_t sampling_points_generated = 0;
};

// True for a command whose words are "fix ID GROUP fsi/sph ...".
bool is_fix_fsi_sph_command(std::span<const std::string> words);

// Creates the fix from the words of its command (variables already substituted) and adds it to
// the instance's fix list, replacing an earlier fsi/sph fix with the same ID. Throws
// std::invalid_argument naming the bad argument (unknown group, bad keyword, bad value).
// A newly added fix is called by LIGGGHTS only after a run with set-up (e.g. "run 0").
void add_fix_fsi_sph(LAMMPS_NS::LAMMPS& lammps, std::span<const std::string> words,
                     std::shared_ptr<CouplingBoundary> boundary);

// Appends (or moves) our internal fix `fsi/ghost_sync` to the end of the fix list. In pre_force
// it forward-communicates ghost atoms after every other pre_force fix has run. Reason: LIGGGHTS
// 3.8's `fix sph/pressure` recomputes the pressure of local atoms in pre_force but not of ghost
// atoms, so a pair across two MPI subdomains would use last step's ghost pressure and a 2-rank
// run would drift from the 1-rank run by ~1e-5 per step (measured). Call it after every script.
void ensure_ghost_sync_last(LAMMPS_NS::LAMMPS& lammps);

}  // namespace fsi::contact
