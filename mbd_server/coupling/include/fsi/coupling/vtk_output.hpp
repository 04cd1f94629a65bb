#pragma once
// The run's ParaView files in DIR/vtk/: fluid particles (fluid.pvd), boundary mesh
// (boundary.pvd), rigid-body frames (bodies.pvd) and, in scenes with ANCF beams, the beams'
// centre lines (beams.pvd: one polyline per beam, kCentreLineSamplesPerElement segments per
// element, with point velocities), one file each per particle snapshot.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>

#include "fsi/coupling/output.hpp"
#include "fsi/mbd/model.hpp"
#include "fsi/output/series.hpp"
#include "fsi/scene/scene.hpp"

namespace fsi::coupling {

class VtkOutput {
 public:
  // Creates the folder.
  explicit VtkOutput(const std::filesystem::path& directory);

  // fluid_forces: dimension values per boundary vertex (static vertices: 0, the client does not
  // send them), the forces that act from the snapshot's step on.
  void write(const ParticleSnapshot& particles, const mbd::Model& model, const mbd::State& state,
             const scene::BoundaryMesh& boundary, std::span<const double> fluid_forces);

  // The structure alone (fsi-server --mbd-only): the boundary mesh (if any, no fluid forces), the
  // rigid bodies' frames (if any) and the beams' centre lines (if any); no fluid series.
  void write_structure(std::uint64_t step, const mbd::Model& model, const mbd::State& state,
                       const scene::BoundaryMesh& boundary);

  // Checkpoints: every series' entries (restore_state removes the files written after it).
  void save_state(output::StateWriter& out) const;
  void restore_state(output::StateReader& in);

  // Polyline segments per beam element in beams.pvd (each element's centre line is a cubic).
  static constexpr int kCentreLineSamplesPerElement = 8;

 private:
  void write_mesh(std::uint64_t step, const mbd::Model& model, const mbd::State& state,
                  const scene::BoundaryMesh& boundary, std::span<const double> fluid_forces);
  void write_bodies(std::uint64_t step, const mbd::Model& model, const mbd::State& state,
                    bool even_without_bodies);
  void write_centre_lines(std::uint64_t step, const mbd::Model& model, const mbd::State& state);

  std::filesystem::path directory_;
  output::Series fluid_, boundary_, bodies_;
  std::optional<output::Series> beams_;  // made at the first snapshot with beams
};

}  // namespace fsi::coupling
