#pragma once
// The run's ParaView files in DIR/vtk/: fluid particles (fluid.pvd), boundary mesh
// (boundary.pvd) and rigid-body frames (bodies.pvd), one file each per particle snapshot.

#include <filesystem>
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

 private:
  output::Series fluid_, boundary_, bodies_;
};

}  // namespace fsi::coupling
