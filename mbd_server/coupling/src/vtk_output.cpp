#include "fsi/coupling/vtk_output.hpp"

#include <vector>

#include "fsi/common/error.hpp"
#include "fsi/mbd/readouts.hpp"
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
    : directory_(directory),
      fluid_(created(directory), "fluid", "vtu"),
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
  write_mesh(particles.step, model, state, boundary, fluid_forces);
  write_bodies(particles.step, model, state, true);
  write_centre_lines(particles.step, model, state);
}

void VtkOutput::write_structure(std::uint64_t step, const mbd::Model& model,
                                const mbd::State& state, const scene::BoundaryMesh& boundary) {
  if (boundary.vertex_count > 0) write_mesh(step, model, state, boundary, {});
  write_bodies(step, model, state, false);
  write_centre_lines(step, model, state);
}

void VtkOutput::write_mesh(std::uint64_t step, const mbd::Model& model, const mbd::State& state,
                           const scene::BoundaryMesh& boundary,
                           std::span<const double> fluid_forces) {
  std::vector<double> positions, velocities;
  scene::boundary_state(boundary, model, state, positions, velocities);
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
  boundary_.write(step, state.time, output::encode_boundary(mesh));
}

void VtkOutput::write_bodies(std::uint64_t step, const mbd::Model& model, const mbd::State& state,
                             bool even_without_bodies) {
  output::BodyFrame frames;
  frames.time = state.time;
  std::vector<double> body_positions, body_velocities, angles;
  for (mbd::BodyId b = 0; model.dimension() == 2 && b < model.body_count(); ++b) {
    if (model.is_beam(b)) continue;  // no rigid frame: its centre line goes to beams.pvd
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
  if (even_without_bodies || !frames.names.empty())
    bodies_.write(step, state.time, output::encode_bodies(frames));
}

void VtkOutput::save_state(output::StateWriter& out) const {
  fluid_.save_state(out);
  boundary_.save_state(out);
  bodies_.save_state(out);
  out.put(beams_.has_value());
  if (beams_) beams_->save_state(out);
}

void VtkOutput::restore_state(output::StateReader& in) {
  fluid_.restore_state(in);
  boundary_.restore_state(in);
  bodies_.restore_state(in);
  if (in.boolean("beam series")) {
    beams_.emplace(directory_, "beams", "vtp");
    beams_->restore_state(in);
  }
}

void VtkOutput::write_centre_lines(std::uint64_t step, const mbd::Model& model,
                                   const mbd::State& state) {
  output::CentreLineFrame lines;
  lines.time = state.time;
  std::vector<std::size_t> counts;
  std::vector<double> positions, velocities;
  for (mbd::BodyId b = 0; model.dimension() == 2 && b < model.body_count(); ++b) {
    if (!model.is_beam(b)) continue;
    const mbd::AncfBeamSpec& beam = model.beam(b);
    const double length = (beam.end - beam.start).norm();
    const int samples = kCentreLineSamplesPerElement * beam.element_count;
    for (int i = 0; i <= samples; ++i) {
      // s = L i / samples, the last exactly L (a point past the beam's end is refused).
      const double s = i == samples ? length : length * i / samples;
      const mbd::BodyPointSpec point{b, {s, 0.0}};
      const Eigen::Vector2d r = point_position(model, state, point).head<2>();
      const Eigen::Vector2d v = point_velocity(model, state, point).head<2>();
      positions.insert(positions.end(), {r.x(), r.y()});
      velocities.insert(velocities.end(), {v.x(), v.y()});
    }
    lines.names.push_back(beam.name);
    counts.push_back(static_cast<std::size_t>(samples + 1));
  }
  if (counts.empty()) return;  // no beams, no beams.pvd
  lines.point_counts = counts;
  lines.positions = positions;
  lines.velocities = velocities;
  if (!beams_) beams_.emplace(directory_, "beams", "vtp");
  beams_->write(step, state.time, output::encode_centre_lines(lines));
}

}  // namespace fsi::coupling
