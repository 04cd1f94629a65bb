#include "fsi/coupling/vtk_output.hpp"

#include <vector>

#include "fsi/common/error.hpp"
#include "fsi/output/vtk_files.hpp"

namespace fsi::coupling {

namespace fs = std::filesystem;

namespace {

fs::path created(const fs::path& directory) {
  std::error_code error;
  fs::create_directories(directory, error);
  if (error) {
    throw Error("cannot create " + directory.string() + ": " + error.message(), "VTK output",
                "choose a writable --output folder");
  }
  return directory;
}

}  // namespace

VtkOutput::VtkOutput(const fs::path& directory)
    : fluid_(created(directory), "fluid", "vtu"),
      boundary_(directory, "boundary", "vtu"),
      bodies_(directory, "bodies", "vtp") {}

void VtkOutput::write(const ParticleSnapshot& particles, const mbd::Model& model,
                      const mbd::State& state, const scene::BoundaryMesh& boundary,
                      std::span<const double> fluid_forces) {
  output::ParticleFrame fluid;
  fluid.dimension = particles.dimension;
  fluid.time = particles.time;
  fluid.ids = particles.ids;
  fluid.positions = particles.positions;
  fluid.velocities = particles.velocities;
  fluid.density = particles.density;
  fluid.pressure = particles.pressure;
  fluid_.write(particles.step, particles.time, output::encode_particles(fluid));

  const auto dimension = static_cast<std::size_t>(boundary.dimension);
  std::vector<double> positions(dimension * boundary.vertex_count), velocities(positions.size());
  if (boundary.dimension == 3) {
    positions = boundary.static_positions;  // every 3D vertex is static (at rest)
  } else {
    model.marker_positions(state, positions);
    model.marker_velocities(state, velocities);
  }
  const std::vector<double> no_forces(positions.size(), 0.0);
  output::BoundaryFrame mesh;
  mesh.dimension = boundary.dimension;
  mesh.time = state.time;
  mesh.positions = positions;
  mesh.velocities = velocities;
  mesh.fluid_forces =
      fluid_forces.size() == positions.size() ? fluid_forces : std::span<const double>(no_forces);
  mesh.dynamic_vertex_count = boundary.dynamic_vertex_count;
  mesh.elements = boundary.elements();
  boundary_.write(particles.step, state.time, output::encode_boundary(mesh));

  output::BodyFrame frames;
  frames.time = state.time;
  std::vector<double> body_positions, body_velocities, angles;
  for (mbd::BodyId b = 0; b < model.body_count(); ++b) {
    frames.names.push_back(model.body(b).name);
    body_positions.push_back(model.coordinate(state, b, mbd::Coordinate::X));
    body_positions.push_back(model.coordinate(state, b, mbd::Coordinate::Y));
    body_velocities.push_back(model.velocity(state, b, mbd::Coordinate::X));
    body_velocities.push_back(model.velocity(state, b, mbd::Coordinate::Y));
    angles.push_back(model.coordinate(state, b, mbd::Coordinate::Angle));
  }
  frames.positions = body_positions;
  frames.velocities = body_velocities;
  frames.angles = angles;
  bodies_.write(particles.step, state.time, output::encode_bodies(frames));
  // ANCF beams (once the model has them): sample each element's centre line r(x) at a few points,
  // fill an output::CentreLineFrame (one line per beam) and write it to a fourth series
  // "beams" (.vtp) here, at the same steps.
}

}  // namespace fsi::coupling
