#pragma once
// The distributed boundary (thesis §7.1; issue 17 item 2; docs/user-guide.md, "Ranks and
// balance"). Rank 0 holds the whole mesh as the server sends it and is the only rank that talks
// to the server. Every rank holds and evaluates only its share (boundary_share.hpp): the elements
// within reach of the particles it owns, plus a margin. Per step, rank 0 sends each rank the
// positions and velocities of its share's dynamic vertices only, and gathers each rank's vertex
// forces onto the whole mesh; the shares are chosen again (collectively) when the decomposition
// changes, a vertex has moved half the margin since the last choice, or a rank's particles come
// within half the margin of the edge of what its share covers.

#include <mpi.h>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "boundary_share.hpp"
#include "fsi/contact/liggghts_fix.hpp"
#include "fsi/protocol/messages.hpp"

namespace LAMMPS_NS {
class LAMMPS;
}

namespace fsi::client {

class DistributedBoundary {
 public:
  DistributedBoundary(MPI_Comm communicator, std::shared_ptr<contact::CouplingBoundary> boundary);

  // Collective. Rank 0 passes the server's whole mesh (it checks it and throws fsi::Error naming
  // the problem), the other ranks a Mesh carrying its settings but no arrays. Every rank's
  // boundary holds no element until select().
  void configure(protocol::Mesh mesh);

  // Rank 0's share is the whole mesh (wall-pressure probes need every sampling point of their
  // patches on one rank, their area being the largest over the ranks). Before select().
  void root_holds_whole_mesh(bool whole) { root_whole_ = whole; }

  // Collective: every rank's share for the sub-domains and particles as they are now, sent with
  // the whole mesh's current positions and velocities. Needs the fix (its wall law's range).
  void select(const LAMMPS_NS::LAMMPS& lammps);

  // Rank 0: the structure rests (equilibration: zero velocities) or moves with the velocities
  // the server sent with the mesh; takes effect at the next select().
  void hold_still(bool still);

  // Rank 0: takes the whole-mesh values of a Step or StepMotion (throws fsi::Error when their
  // counts do not fit the mesh). Returns true when the shares must be chosen again before the
  // step (a vertex moved half the margin, or a rank asked for it).
  bool take_whole(const protocol::Message& message);
  // Collective: this rank's part of rank 0's Step or StepMotion (`whole` on rank 0 only).
  protocol::Message scatter(const protocol::Message* whole, std::uint16_t type);

  // Collective: the ranks' vertex forces (their shares' dynamic vertices, `dimension` values
  // each) added onto the whole mesh's dynamic vertices, rank after rank, on rank 0 (empty
  // elsewhere).
  std::vector<double> gather_forces(std::span<const double> local_forces);

  // This rank: has one of its particles come within half the margin of the edge of the box its
  // share covers (after a step)? Rank 0: request_selection() when a rank answered yes.
  bool particles_near_edge(const LAMMPS_NS::LAMMPS& lammps) const;
  void request_selection() { selection_due_ = true; }

  // The whole-mesh index of each element of this rank's share.
  std::span<const std::uint32_t> element_ids() const { return share_elements_; }

  // Collective: a line for the log (rank 0) on the shares held per rank.
  std::string summary() const;

  double margin() const { return margin_; }

 private:
  contact::CouplingBoundary& boundary() { return *boundary_; }
  std::vector<double> whole_velocities() const;
  // The bytes of this rank's share (mesh, velocities, forces, element ids), and rank 0's of the
  // whole mesh and the shares' index lists.
  double share_bytes() const;
  double whole_bytes() const;
  // 3D refinement options 2 and 3: the levels fixed from the whole mesh travel with the shares.
  bool pre_refined() const;

  MPI_Comm communicator_;
  int rank_ = 0;
  int ranks_ = 1;
  std::shared_ptr<contact::CouplingBoundary> boundary_;
  int dimension_ = 2;
  std::size_t whole_dynamic_vertices_ = 0;
  std::size_t whole_elements_ = 0;
  // Rank 0: the whole mesh as the latest message left it, the pre-refinement levels (3D
  // options 2, 3), every rank's share, and the dynamic vertices' positions at the last selection.
  protocol::Mesh whole_;
  std::vector<std::uint8_t> whole_pre_refinement_;
  bool still_ = false;
  bool root_whole_ = false;
  std::vector<BoundaryShare> shares_;
  std::vector<double> positions_at_selection_;
  bool selection_due_ = false;
  std::uint64_t selections_while_moving_ = 0;
  // This rank.
  std::vector<std::uint32_t> share_elements_;
  ShareBox base_;  // sub-domain and particles at the selection
  double margin_ = 0.0;
  std::uint64_t selections_ = 0;
  std::uint64_t most_elements_held_ = 0;
};

}  // namespace fsi::client
