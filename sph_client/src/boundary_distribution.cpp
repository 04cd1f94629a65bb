#include "boundary_distribution.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>
#include <utility>
#include <variant>

// LIGGGHTS 3.8 headers (Debian's libliggghts-dev).
#include "atom.h"
#include "domain.h"
#include "fsi/common/error.hpp"
#include "fsi/contact/wall_contact_3d.hpp"
#include "lammps.h"

namespace fsi::client {
namespace {

constexpr int kShareTag = 7301;

WholeMesh whole_view(const protocol::Mesh& mesh) {
  return {static_cast<int>(mesh.dimension), mesh.positions, mesh.element_vertices,
          mesh.dynamic_vertex_count};
}

// What this rank covers: its sub-domain and the bounding box of its particles.
ShareBox sub_domain_and_particles(const LAMMPS_NS::LAMMPS& lammps, int dimension) {
  const LAMMPS_NS::Domain& domain = *lammps.domain;
  ShareBox box;
  box.include(std::span<const double>(domain.sublo, 3), dimension);
  box.include(std::span<const double>(domain.subhi, 3), dimension);
  const LAMMPS_NS::Atom& atom = *lammps.atom;
  if (atom.nlocal > 0) {
    box.include(
        bounding_box(std::span<const double>(atom.x[0], static_cast<std::size_t>(3 * atom.nlocal)),
                     3),
        dimension);
  }
  return box;
}

SharePeriodicity periodicity_of(const LAMMPS_NS::LAMMPS& lammps) {
  SharePeriodicity periodicity;
  for (int k = 0; k < 3; ++k) {
    periodicity.periodic[k] = lammps.domain->periodicity[k] != 0;
    periodicity.period[k] = lammps.domain->boxhi[k] - lammps.domain->boxlo[k];
  }
  return periodicity;
}

template <class T>
MPI_Datatype mpi_type();
template <>
MPI_Datatype mpi_type<double>() {
  return MPI_DOUBLE;
}
template <>
MPI_Datatype mpi_type<std::uint32_t>() {
  return MPI_UINT32_T;
}
template <>
MPI_Datatype mpi_type<std::uint8_t>() {
  return MPI_UINT8_T;
}

template <class T>
void send_vector(const std::vector<T>& values, int to, MPI_Comm communicator) {
  MPI_Send(values.data(), static_cast<int>(values.size()), mpi_type<T>(), to, kShareTag,
           communicator);
}

template <class T>
std::vector<T> receive_vector(std::size_t count, MPI_Comm communicator) {
  std::vector<T> values(count);
  MPI_Recv(values.data(), static_cast<int>(count), mpi_type<T>(), 0, kShareTag, communicator,
           MPI_STATUS_IGNORE);
  return values;
}

// The values of `vertices` in every node block of a node-major array.
std::vector<double> node_blocks(std::span<const double> whole, std::size_t nodes,
                                std::size_t whole_values, const BoundaryShare& share,
                                int dimension) {
  std::vector<double> local;
  local.reserve(nodes * share.dynamic_vertices * static_cast<std::size_t>(dimension));
  for (std::size_t n = 0; n < nodes; ++n) {
    const std::vector<double> block =
        share_values(whole.subspan(n * whole_values, whole_values), share.vertices,
                     share.dynamic_vertices, dimension);
    local.insert(local.end(), block.begin(), block.end());
  }
  return local;
}

}  // namespace

DistributedBoundary::DistributedBoundary(MPI_Comm communicator,
                                         std::shared_ptr<contact::CouplingBoundary> boundary)
    : communicator_(communicator), boundary_(std::move(boundary)) {
  MPI_Comm_rank(communicator_, &rank_);
  MPI_Comm_size(communicator_, &ranks_);
}

void DistributedBoundary::configure(protocol::Mesh mesh) {
  dimension_ = static_cast<int>(mesh.dimension);
  contact::CouplingBoundary& b = boundary();
  b.dynamic_vertex_count = 0;
  b.refinement_resolution = mesh.refinement_resolution;
  b.refinement_option = static_cast<int>(mesh.refinement_option);
  // Rank 0 checks the whole mesh; the counts and the drawn extent go to every rank.
  std::array<double, 2 * 3 + 2> shared{};
  if (rank_ == 0) {
    try {
      contact::CouplingBoundary check;
      check.assign(dimension_, mesh.positions, mesh.velocities, mesh.element_vertices);
    } catch (const std::invalid_argument& bad) {
      throw Error(std::string("boundary mesh from the server is inconsistent: ") + bad.what(),
                  "set-up (mesh)", "check the scene's meshes");
    }
    const ShareBox drawn = bounding_box(mesh.positions, dimension_);
    for (int k = 0; k < 3; ++k) {
      shared[k] = k < dimension_ && !drawn.empty(dimension_) ? drawn.low[k] : 0.0;
      shared[3 + k] = k < dimension_ && !drawn.empty(dimension_) ? drawn.high[k] : 0.0;
    }
    shared[6] = static_cast<double>(mesh.dynamic_vertex_count);
    shared[7] = static_cast<double>(mesh.element_vertices.size() / mesh.dimension);
    if (pre_refined()) {
      contact::ContactSettings3D settings;
      settings.refinement_option = b.refinement_option;
      settings.refinement_resolution = b.refinement_resolution;
      contact::BoundaryMesh3D whole_mesh;
      whole_mesh.positions = mesh.positions;
      whole_mesh.velocities = mesh.velocities;
      whole_mesh.triangles = mesh.element_vertices;
      try {
        whole_pre_refinement_ = contact::pre_refinement_levels(settings, whole_mesh);
      } catch (const std::invalid_argument& bad) {
        throw Error(std::string("the boundary mesh cannot be pre-refined: ") + bad.what(),
                    "set-up (mesh)", "choose Coupling.refinement_resolution to suit the mesh");
      }
    }
    whole_ = std::move(mesh);
  }
  MPI_Bcast(shared.data(), static_cast<int>(shared.size()), MPI_DOUBLE, 0, communicator_);
  whole_dynamic_vertices_ = static_cast<std::size_t>(shared[6]);
  whole_elements_ = static_cast<std::size_t>(shared[7]);
  b.drawn_bounds.clear();
  if (whole_elements_ > 0) {
    for (int corner = 0; corner < 2; ++corner) {
      for (int k = 0; k < dimension_; ++k)
        b.drawn_bounds.push_back(shared[3 * corner + k]);
    }
  }
  b.assign(dimension_, {}, {}, {});
  b.share_pending = true;
}

void DistributedBoundary::hold_still(bool still) {
  still_ = still;
}

bool DistributedBoundary::pre_refined() const {
  return dimension_ == 3 &&
         (boundary_->refinement_option == 2 || boundary_->refinement_option == 3);
}

std::vector<double> DistributedBoundary::whole_velocities() const {
  if (!still_) return whole_.velocities;
  return std::vector<double>(whole_.velocities.size(), 0.0);
}

void DistributedBoundary::select(const LAMMPS_NS::LAMMPS& lammps) {
  contact::CouplingBoundary& b = boundary();
  const double range = b.law.range();
  margin_ = range;
  base_ = sub_domain_and_particles(lammps, dimension_);
  const ShareBox covered = base_.widened(margin_, dimension_);
  std::array<double, 7> mine{};
  for (int k = 0; k < 3; ++k) {
    mine[k] = covered.low[k];
    mine[3 + k] = covered.high[k];
  }
  mine[6] = covered.empty(dimension_) ? 1.0 : 0.0;
  std::vector<double> all(rank_ == 0 ? 7 * static_cast<std::size_t>(ranks_) : 0);
  MPI_Gather(mine.data(), 7, MPI_DOUBLE, all.data(), 7, MPI_DOUBLE, 0, communicator_);

  // Rank 0 chooses every share and sends each its mesh; then its own.
  LocalMesh own;
  std::vector<std::uint8_t> own_levels;
  std::array<std::uint64_t, 3> counts{};  // vertices, dynamic ones, elements
  if (rank_ == 0) {
    const WholeMesh view = whole_view(whole_);
    const SharePeriodicity periodicity = periodicity_of(lammps);
    const std::vector<double> velocities = whole_velocities();
    shares_.assign(static_cast<std::size_t>(ranks_), {});
    for (int r = ranks_ - 1; r >= 0; --r) {
      const auto at = static_cast<std::size_t>(7 * r);
      ShareBox box;
      if (all[at + 6] == 0.0) {
        for (int k = 0; k < 3; ++k) {
          box.low[k] = all[at + k];
          box.high[k] = all[at + 3 + k];
        }
      }
      BoundaryShare& share = shares_[static_cast<std::size_t>(r)];
      share = r == 0 && root_whole_ ? whole_share(view)
                                    : select_share(view, box, range + margin_, periodicity);
      LocalMesh local = local_mesh(view, velocities, share);
      std::vector<std::uint8_t> levels;
      if (!whole_pre_refinement_.empty()) {
        for (const std::uint32_t element : share.elements)
          levels.push_back(whole_pre_refinement_[element]);
      }
      if (r == 0) {
        own = std::move(local);
        own_levels = std::move(levels);
        counts = {share.vertices.size(), share.dynamic_vertices, share.elements.size()};
        continue;
      }
      const std::array<std::uint64_t, 3> sizes{share.vertices.size(), share.dynamic_vertices,
                                               share.elements.size()};
      MPI_Send(sizes.data(), 3, MPI_UINT64_T, r, kShareTag, communicator_);
      send_vector(share.elements, r, communicator_);
      send_vector(local.positions, r, communicator_);
      send_vector(local.velocities, r, communicator_);
      send_vector(local.elements, r, communicator_);
      send_vector(levels, r, communicator_);
    }
    share_elements_ = shares_[0].elements;
    positions_at_selection_.assign(
        whole_.positions.begin(),
        whole_.positions.begin() + static_cast<long>(whole_dynamic_vertices_ * dimension_));
    selection_due_ = false;
  } else {
    MPI_Recv(counts.data(), 3, MPI_UINT64_T, 0, kShareTag, communicator_, MPI_STATUS_IGNORE);
    const auto d = static_cast<std::size_t>(dimension_);
    share_elements_ = receive_vector<std::uint32_t>(counts[2], communicator_);
    own.positions = receive_vector<double>(counts[0] * d, communicator_);
    own.velocities = receive_vector<double>(counts[0] * d, communicator_);
    own.elements = receive_vector<std::uint32_t>(counts[2] * d, communicator_);
    own_levels = receive_vector<std::uint8_t>(pre_refined() ? counts[2] : 0, communicator_);
  }
  b.assign(dimension_, std::move(own.positions), std::move(own.velocities),
           std::move(own.elements));
  b.dynamic_vertex_count = counts[1];
  b.pre_refinement = std::move(own_levels);
  b.coverage.active = !covered.empty(dimension_);
  for (int k = 0; k < 3; ++k) {
    b.coverage.low[k] = k < dimension_ ? covered.low[k] : -std::numeric_limits<double>::max();
    b.coverage.high[k] = k < dimension_ ? covered.high[k] : std::numeric_limits<double>::max();
  }
  b.share_pending = false;
  ++b.share_generation;
  ++selections_;
  most_elements_held_ = std::max<std::uint64_t>(most_elements_held_, counts[2]);
}

bool DistributedBoundary::take_whole(const protocol::Message& message) {
  const auto d = static_cast<std::size_t>(dimension_);
  const std::size_t values = whole_dynamic_vertices_ * d;
  double moved = 0.0;
  if (const auto* step = std::get_if<protocol::Step>(&message)) {
    if (step->positions.size() != values || step->velocities.size() != values) {
      throw Error("Step message carries " + std::to_string(step->positions.size() / d) +
                      " vertices, the mesh has " + std::to_string(whole_dynamic_vertices_) +
                      " dynamic ones",
                  "step " + std::to_string(step->step), "use matching server and client releases");
    }
    std::copy(step->positions.begin(), step->positions.end(), whole_.positions.begin());
    std::copy(step->velocities.begin(), step->velocities.end(), whole_.velocities.begin());
    moved = largest_displacement(step->positions, positions_at_selection_, dimension_);
  } else if (const auto* motion = std::get_if<protocol::StepMotion>(&message)) {
    const std::size_t nodes = motion->nodes.size();
    if (nodes == 0 || motion->positions.size() != nodes * values ||
        motion->velocities.size() != nodes * values) {
      throw Error("StepMotion message carries " + std::to_string(motion->positions.size() / d) +
                      " vertex values over " + std::to_string(nodes) + " nodes, the mesh has " +
                      std::to_string(whole_dynamic_vertices_) + " dynamic vertices",
                  "StepMotion of step " + std::to_string(motion->step),
                  "use matching server and client releases");
    }
    const std::span<const double> positions(motion->positions);
    for (std::size_t n = 0; n < nodes; ++n) {
      moved = std::max(moved, largest_displacement(positions.subspan(n * values, values),
                                                   positions_at_selection_, dimension_));
    }
    std::copy_n(motion->positions.end() - static_cast<long>(values), values,
                whole_.positions.begin());
    std::copy_n(motion->velocities.end() - static_cast<long>(values), values,
                whole_.velocities.begin());
  }
  const bool due = selection_due_ || moved > 0.5 * margin_;
  if (due) ++selections_while_moving_;
  return due;
}

protocol::Message DistributedBoundary::scatter(const protocol::Message* whole, std::uint16_t type) {
  // Rank 0 encodes each rank's part as a message of the same type; the bytes travel by Scatterv.
  std::vector<std::byte> bytes;
  std::vector<int> sizes, offsets;
  if (rank_ == 0) {
    for (int r = 0; r < ranks_; ++r) {
      const BoundaryShare& share = shares_[static_cast<std::size_t>(r)];
      std::vector<std::byte> encoded;
      if (const auto* step = std::get_if<protocol::Step>(whole)) {
        protocol::Step local{step->step, step->time, step->time_step, {}, {}};
        local.positions =
            share_values(step->positions, share.vertices, share.dynamic_vertices, dimension_);
        local.velocities =
            share_values(step->velocities, share.vertices, share.dynamic_vertices, dimension_);
        encoded = protocol::encode(local);
      } else {
        const auto& motion = std::get<protocol::StepMotion>(*whole);
        const std::size_t values = whole_dynamic_vertices_ * static_cast<std::size_t>(dimension_);
        protocol::StepMotion local{
            motion.step, motion.time, motion.time_step, motion.substeps, motion.nodes, {}, {}};
        local.positions =
            node_blocks(motion.positions, motion.nodes.size(), values, share, dimension_);
        local.velocities =
            node_blocks(motion.velocities, motion.nodes.size(), values, share, dimension_);
        encoded = protocol::encode(local);
      }
      offsets.push_back(static_cast<int>(bytes.size()));
      sizes.push_back(static_cast<int>(encoded.size()));
      bytes.insert(bytes.end(), encoded.begin(), encoded.end());
    }
  }
  int size = 0;
  MPI_Scatter(sizes.data(), 1, MPI_INT, &size, 1, MPI_INT, 0, communicator_);
  std::vector<std::byte> mine(static_cast<std::size_t>(size));
  MPI_Scatterv(bytes.data(), sizes.data(), offsets.data(), MPI_BYTE, mine.data(), size, MPI_BYTE, 0,
               communicator_);
  return protocol::decode(static_cast<protocol::MessageType>(type), mine);
}

std::vector<double> DistributedBoundary::gather_forces(std::span<const double> local_forces) {
  const auto d = static_cast<std::size_t>(dimension_);
  const int mine = static_cast<int>(boundary().dynamic_vertex_count * d);
  std::vector<int> sizes, offsets;
  std::vector<double> all;
  if (rank_ == 0) {
    int total = 0;
    for (const BoundaryShare& share : shares_) {
      offsets.push_back(total);
      sizes.push_back(static_cast<int>(share.dynamic_vertices * d));
      total += sizes.back();
    }
    all.resize(static_cast<std::size_t>(total));
  }
  std::vector<double> sent(local_forces.begin(),
                           local_forces.begin() + std::min<long>(mine, local_forces.size()));
  sent.resize(static_cast<std::size_t>(mine), 0.0);
  MPI_Gatherv(sent.data(), mine, MPI_DOUBLE, all.data(), sizes.data(), offsets.data(), MPI_DOUBLE,
              0, communicator_);
  if (rank_ != 0) return {};
  std::vector<double> whole(whole_dynamic_vertices_ * d, 0.0);
  for (std::size_t r = 0; r < shares_.size(); ++r) {
    const BoundaryShare& share = shares_[r];
    add_share_values(std::span<const double>(all).subspan(static_cast<std::size_t>(offsets[r]),
                                                          static_cast<std::size_t>(sizes[r])),
                     share.vertices, share.dynamic_vertices, dimension_, whole);
  }
  return whole;
}

bool DistributedBoundary::particles_near_edge(const LAMMPS_NS::LAMMPS& lammps) const {
  const LAMMPS_NS::Atom& atom = *lammps.atom;
  const ShareBox inner = base_.widened(0.5 * margin_, dimension_);
  for (int i = 0; i < atom.nlocal; ++i) {
    if (!inner.contains(std::span<const double>(atom.x[i], 3), dimension_)) return true;
  }
  return false;
}

namespace {

template <class T>
double bytes_of(const std::vector<T>& values) {
  return static_cast<double>(values.capacity() * sizeof(T));
}

}  // namespace

double DistributedBoundary::share_bytes() const {
  const contact::CouplingBoundary& b = *boundary_;
  return bytes_of(b.mesh.positions) + bytes_of(b.mesh.velocities) + bytes_of(b.mesh.segments) +
         bytes_of(b.mesh3d.positions) + bytes_of(b.mesh3d.velocities) +
         bytes_of(b.mesh3d.triangles) + bytes_of(b.vertex_forces) + bytes_of(b.pre_refinement) +
         bytes_of(share_elements_);
}

double DistributedBoundary::whole_bytes() const {
  double bytes = bytes_of(whole_.positions) + bytes_of(whole_.velocities) +
                 bytes_of(whole_.element_vertices) + bytes_of(whole_pre_refinement_) +
                 bytes_of(positions_at_selection_);
  for (const BoundaryShare& share : shares_)
    bytes += bytes_of(share.elements) + bytes_of(share.vertices);
  return bytes;
}

std::string DistributedBoundary::summary() const {
  const std::array<double, 4> mine{
      static_cast<double>(share_elements_.size()), static_cast<double>(most_elements_held_),
      static_cast<double>(boundary_->positions().size() / static_cast<std::size_t>(dimension_)),
      share_bytes()};
  constexpr std::size_t kValues = mine.size();
  std::vector<double> all(rank_ == 0 ? kValues * static_cast<std::size_t>(ranks_) : 0);
  MPI_Gather(mine.data(), kValues, MPI_DOUBLE, all.data(), kValues, MPI_DOUBLE, 0, communicator_);
  if (rank_ != 0) return {};
  std::string held, most, vertices, kib;
  for (std::size_t r = 0; r < static_cast<std::size_t>(ranks_); ++r) {
    const char* separator = r == 0 ? "" : " / ";
    held += fmt::format("{}{:.0f}", separator, all[kValues * r]);
    most += fmt::format("{}{:.0f}", separator, all[kValues * r + 1]);
    vertices += fmt::format("{}{:.0f}", separator, all[kValues * r + 2]);
    kib += fmt::format("{}{:.1f}", separator, all[kValues * r + 3] / 1024.0);
  }
  return fmt::format(
      "boundary mesh: {} of {} elements held per rank at the end (at most {}; vertices {} of "
      "{}), {} selection(s) of the shares, {} of them during the coupled steps (margin {:.6g} "
      "m); the shares take {} KiB per rank, rank 0 keeps the whole mesh besides ({:.1f} KiB){}",
      held, whole_elements_, most, vertices, whole_.vertex_count(), selections_,
      selections_while_moving_, margin_, kib, whole_bytes() / 1024.0,
      root_whole_ ? "; rank 0's share is the whole mesh (wall-pressure probes)" : "");
}

}  // namespace fsi::client
