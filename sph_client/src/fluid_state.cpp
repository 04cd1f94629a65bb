#include "fluid_state.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <span>
#include <type_traits>
#include <vector>

#include "atom.h"
#include "atom_vec.h"
#include "comm.h"
#include "domain.h"
#include "fix.h"
#include "fix_sph_density_corr.h"
#include "lammps.h"
#include "memory.h"
#include "modify.h"
#include "update.h"

#include "fsi/common/error.hpp"

namespace fsi::client {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the checkpoint stores little-endian integers and IEEE-754 doubles as they lie in "
              "memory");

constexpr char kMagic[8] = {'F', 'S', 'I', 'F', 'L', 'U', 'I', 'D'};
constexpr const char* kShepardStyle = "sph/density/corr";
// Largest chunk one MPI call moves (counts are int).
constexpr std::size_t kChunk = std::size_t{1} << 30;

// ---- The Shepard filter's step counter ------------------------------------------------------
// FixSphDensityCorr filters when its private counter `ago`, incremented at every pre_force (not
// at set-up) and starting at 0 when the fix is created, reaches `every`. It is not part of
// LIGGGHTS' restart files and not derived from the step number, so a resumed process (fix
// created afresh) filters at other steps than the uninterrupted run unless the counter travels
// with the particles. Both members are private; an explicit template instantiation may name
// private members ([temp.spec.general]/6), which gives us pointers to them without changing
// LIGGGHTS. The layout is that of the installed header, which is the library's own.
template <typename Tag, typename Tag::type Member>
struct PrivateMember {
  friend typename Tag::type member_pointer(Tag) { return Member; }
};
struct ShepardCounter {
  using type = int LAMMPS_NS::FixSphDensityCorr::*;
  friend type member_pointer(ShepardCounter);
};
struct ShepardEvery {
  using type = int LAMMPS_NS::FixSphDensityCorr::*;
  friend type member_pointer(ShepardEvery);
};
template struct PrivateMember<ShepardCounter, &LAMMPS_NS::FixSphDensityCorr::ago>;
template struct PrivateMember<ShepardEvery, &LAMMPS_NS::FixSphDensityCorr::every>;

LAMMPS_NS::FixSphDensityCorr* as_shepard_filter(LAMMPS_NS::Fix* fix) {
  if (std::strcmp(fix->style, kShepardStyle) != 0) return nullptr;
  return static_cast<LAMMPS_NS::FixSphDensityCorr*>(fix);
}

// ---- What the checkpoint holds ----------------------------------------------------------------

struct CarriedFix {  // a fix whose per-atom restart data is part of every record
  std::string id, style;
  bool operator==(const CarriedFix&) const = default;
};

struct FixCounter {  // a Shepard filter's counter
  std::string id;
  std::int32_t every = 0, ago = 0;
};

struct Header {
  std::uint32_t version = kFluidStateFormatVersion;
  std::int32_t dimension = 0;
  std::string atom_style;
  std::int64_t step = 0;       // update->ntimestep
  std::int64_t time_step = 0;  // update->atimestep: the step at which `time` was last updated
  double time = 0.0;           // update->atime
  std::uint64_t record_count = 0;
  std::uint64_t dropped = 0;  // particles outside a fixed face of the box, left out
  std::vector<CarriedFix> carried;
  std::vector<FixCounter> counters;
};

struct Record {
  std::int64_t tag = 0;
  std::size_t offset = 0;  // into the records' doubles
  std::size_t length = 0;  // doubles, pack_restart's own count (its first value)
};

struct FluidState {
  Header header;
  std::vector<Record> records;
  std::vector<double> values;
};

// ---- Bytes ------------------------------------------------------------------------------------

class Writer {
 public:
  template <typename T>
  void put(T value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* raw = reinterpret_cast<const char*>(&value);
    bytes_.append(raw, sizeof value);
  }
  void put_text(const std::string& text) {
    put(static_cast<std::uint32_t>(text.size()));
    bytes_ += text;
  }
  void put_doubles(const double* values, std::size_t count) {
    bytes_.append(reinterpret_cast<const char*>(values), count * sizeof(double));
  }
  void put_raw(const char* raw, std::size_t count) { bytes_.append(raw, count); }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

constexpr const char* kWhereBytes = "fluid checkpoint (restore_fluid_state)";
constexpr const char* kFixBytes =
    "the fluid part of the checkpoint is damaged or was not written by capture_fluid_state: "
    "resume from an intact checkpoint";

class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}
  template <typename T>
  T get(const char* what) {
    T value;
    need(sizeof value, what);
    std::memcpy(&value, bytes_.data() + at_, sizeof value);
    at_ += sizeof value;
    return value;
  }
  std::string get_text(const char* what) {
    const auto size = get<std::uint32_t>(what);
    if (size > 4096) {
      throw Error(std::string("implausible length ") + std::to_string(size) + " of " + what,
                  kWhereBytes, kFixBytes);
    }
    need(size, what);
    std::string text(bytes_.substr(at_, size));
    at_ += size;
    return text;
  }
  void get_doubles(double* values, std::size_t count, const char* what) {
    need(count * sizeof(double), what);
    std::memcpy(values, bytes_.data() + at_, count * sizeof(double));
    at_ += count * sizeof(double);
  }
  std::size_t remaining() const { return bytes_.size() - at_; }

 private:
  void need(std::size_t count, const char* what) const {
    if (bytes_.size() - at_ < count) {
      throw Error(std::string("the bytes end inside ") + what + " (at byte " + std::to_string(at_) +
                      " of " + std::to_string(bytes_.size()) + ")",
                  kWhereBytes, kFixBytes);
    }
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
};

std::string serialize(const FluidState& state) {
  const Header& header = state.header;
  Writer out;
  out.put_raw(kMagic, sizeof kMagic);
  out.put(header.version);
  out.put(header.dimension);
  out.put_text(header.atom_style);
  out.put(header.step);
  out.put(header.time_step);
  out.put(header.time);
  out.put(header.record_count);
  out.put(header.dropped);
  out.put(static_cast<std::uint32_t>(header.carried.size()));
  for (const CarriedFix& fix : header.carried) {
    out.put_text(fix.id);
    out.put_text(fix.style);
  }
  out.put(static_cast<std::uint32_t>(header.counters.size()));
  for (const FixCounter& counter : header.counters) {
    out.put_text(counter.id);
    out.put(counter.every);
    out.put(counter.ago);
  }
  for (const Record& record : state.records) {
    out.put(record.tag);
    out.put(static_cast<std::uint32_t>(record.length));
    out.put_doubles(state.values.data() + record.offset, record.length);
  }
  return out.take();
}

FluidState parse(std::string_view bytes) {
  Reader in(bytes);
  char magic[sizeof kMagic];
  for (char& c : magic)
    c = in.get<char>("the magic bytes");
  if (std::memcmp(magic, kMagic, sizeof kMagic) != 0) {
    throw Error("these bytes are not a fluid state (no FSIFLUID magic)", kWhereBytes, kFixBytes);
  }
  FluidState state;
  Header& header = state.header;
  header.version = in.get<std::uint32_t>("the format version");
  if (header.version != kFluidStateFormatVersion) {
    throw Error("fluid state format version " + std::to_string(header.version) +
                    ", this fsi-client reads version " + std::to_string(kFluidStateFormatVersion),
                kWhereBytes, "resume with the fsi-client release that wrote the checkpoint");
  }
  header.dimension = in.get<std::int32_t>("the dimension");
  header.atom_style = in.get_text("the atom style");
  header.step = in.get<std::int64_t>("the step");
  header.time_step = in.get<std::int64_t>("the time's step");
  header.time = in.get<double>("the time");
  header.record_count = in.get<std::uint64_t>("the record count");
  header.dropped = in.get<std::uint64_t>("the count of dropped particles");
  const auto carried = in.get<std::uint32_t>("the count of carried fixes");
  if (carried > 1000) throw Error("implausible count of carried fixes", kWhereBytes, kFixBytes);
  for (std::uint32_t i = 0; i < carried; ++i) {
    CarriedFix fix;
    fix.id = in.get_text("a carried fix's id");
    fix.style = in.get_text("a carried fix's style");
    header.carried.push_back(std::move(fix));
  }
  const auto counters = in.get<std::uint32_t>("the count of fix counters");
  if (counters > 1000) throw Error("implausible count of fix counters", kWhereBytes, kFixBytes);
  for (std::uint32_t i = 0; i < counters; ++i) {
    FixCounter counter;
    counter.id = in.get_text("a fix counter's id");
    counter.every = in.get<std::int32_t>("a fix counter's period");
    counter.ago = in.get<std::int32_t>("a fix counter's value");
    header.counters.push_back(std::move(counter));
  }
  // Each record is at least a tag, a length and four doubles (length, x, y, z).
  if (header.record_count > in.remaining() / (8 + 4 + 4 * sizeof(double))) {
    throw Error("the header announces " + std::to_string(header.record_count) +
                    " particle records but only " + std::to_string(in.remaining()) +
                    " bytes follow",
                kWhereBytes, kFixBytes);
  }
  state.records.reserve(header.record_count);
  std::int64_t previous_tag = 0;
  for (std::uint64_t i = 0; i < header.record_count; ++i) {
    Record record;
    record.tag = in.get<std::int64_t>("a record's tag");
    record.length = in.get<std::uint32_t>("a record's length");
    if (record.tag <= previous_tag || record.tag > INT_MAX) {
      throw Error("record " + std::to_string(i) + " has tag " + std::to_string(record.tag) +
                      " after tag " + std::to_string(previous_tag) +
                      " (tags must increase and fit LIGGGHTS' int)",
                  kWhereBytes, kFixBytes);
    }
    if (record.length < 4 || record.length > 100000) {
      throw Error("record " + std::to_string(i) + " (tag " + std::to_string(record.tag) +
                      ") has an implausible length of " + std::to_string(record.length) + " values",
                  kWhereBytes, kFixBytes);
    }
    previous_tag = record.tag;
    record.offset = state.values.size();
    state.values.resize(record.offset + record.length);
    in.get_doubles(state.values.data() + record.offset, record.length, "a particle record");
    if (state.values[record.offset] != static_cast<double>(record.length)) {
      throw Error("record " + std::to_string(i) + " (tag " + std::to_string(record.tag) +
                      ") does not begin with its own length",
                  kWhereBytes, kFixBytes);
    }
    state.records.push_back(record);
  }
  if (in.remaining() != 0) {
    throw Error("the header announces " + std::to_string(header.record_count) +
                    " particle records but " + std::to_string(in.remaining()) +
                    " bytes follow the last one",
                kWhereBytes, kFixBytes);
  }
  return state;
}

// ---- Checks on the LIGGGHTS instance ------------------------------------------------------------

std::string fix_name(const LAMMPS_NS::Fix& fix) {
  return "fix '" + std::string(fix.id) + "' (style " + fix.style + ")";
}

bool listed(const int* list, int count, int index) {
  return std::find(list, list + count, index) != list + count;
}

// The fixes whose per-atom restart data AtomVec::pack_restart appends to each record, in order.
std::vector<CarriedFix> carried_fixes(const LAMMPS_NS::LAMMPS& lammps) {
  std::vector<CarriedFix> carried;
  const auto& atom = *lammps.atom;
  for (int k = 0; k < atom.nextra_restart; ++k) {
    const LAMMPS_NS::Fix& fix = *lammps.modify->fix[atom.extra_restart[k]];
    carried.push_back({fix.id, fix.style});
  }
  return carried;
}

std::vector<FixCounter> fix_counters(const LAMMPS_NS::LAMMPS& lammps) {
  std::vector<FixCounter> counters;
  for (int j = 0; j < lammps.modify->nfix; ++j) {
    if (auto* filter = as_shepard_filter(lammps.modify->fix[j])) {
      counters.push_back({filter->id, filter->*member_pointer(ShepardEvery{}),
                          filter->*member_pointer(ShepardCounter{})});
    }
  }
  return counters;
}

// Every fix that keeps per-atom values must have them in the records (restart callback), or the
// values would be lost (or, worse, left from whichever particle had the slot before).
void check_per_atom_state_is_carried(const LAMMPS_NS::LAMMPS& lammps, const char* where) {
  const auto& atom = *lammps.atom;
  const auto& modify = *lammps.modify;
  std::string problems;
  for (int j = 0; j < modify.nfix; ++j) {
    const LAMMPS_NS::Fix& fix = *modify.fix[j];
    const bool carried = listed(atom.extra_restart, atom.nextra_restart, j);
    const bool per_atom =
        fix.restart_peratom || fix.create_attribute || listed(atom.extra_grow, atom.nextra_grow, j);
    if (per_atom && !carried) {
      problems += "\n  " + fix_name(fix) + " keeps per-atom values" +
                  (fix.restart_peratom ? " with restart data" : "") +
                  (fix.create_attribute ? " (set for new particles)" : "") +
                  " that no particle record carries";
    }
  }
  if (!problems.empty()) {
    throw Error("the fluid state cannot be checkpointed exactly:" + problems, where,
                "give such a fix restart data (e.g. `fix property/atom ... yes ...`), or remove "
                "it before the checkpoint; extend fluid_state.cpp if its values must survive");
  }
}

void check_instance(const LAMMPS_NS::LAMMPS& lammps, const char* where) {
  if (!lammps.domain->box_exist || lammps.atom->avec == nullptr) {
    throw Error("LIGGGHTS has no simulation box yet", where,
                "run script 1 (create_box) before the fluid state is captured or restored");
  }
  if (lammps.domain->triclinic) {
    throw Error("triclinic boxes are not supported", where, "use an orthogonal box");
  }
  if (!lammps.atom->tag_enable) {
    throw Error("the particles have no IDs", where, "do not use `atom_modify id no`");
  }
  check_per_atom_state_is_carried(lammps, where);
}

// A particle beyond a fixed face of the box: LIGGGHTS' next exchange (comm->exchange keeps
// sublo <= x < subhi) deletes it as lost.
bool outside_fixed_face(const LAMMPS_NS::Domain& domain, const double* x) {
  for (int k = 0; k < 3; ++k) {
    if (domain.periodicity[k]) continue;
    if (domain.boundary[k][0] == 1 && x[k] < domain.boxlo[k]) return true;
    if (domain.boundary[k][1] == 1 && x[k] >= domain.boxhi[k]) return true;
  }
  return false;
}

// x with each periodic coordinate shifted once into the box, as Domain::pbc() will at set-up.
std::array<double, 3> mapped_into_box(const LAMMPS_NS::Domain& domain, const double* x) {
  std::array<double, 3> mapped{x[0], x[1], x[2]};
  for (int k = 0; k < 3; ++k) {
    if (!domain.periodicity[k]) continue;
    if (mapped[k] < domain.boxlo[k]) mapped[k] += domain.prd[k];
    if (mapped[k] >= domain.boxhi[k]) {
      mapped[k] -= domain.prd[k];
      mapped[k] = std::max(mapped[k], domain.boxlo[k]);
    }
  }
  return mapped;
}

std::string format_double(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

// ---- MPI helpers --------------------------------------------------------------------------------

int rank_of(MPI_Comm communicator) {
  int rank = 0;
  MPI_Comm_rank(communicator, &rank);
  return rank;
}

int size_of(MPI_Comm communicator) {
  int size = 1;
  MPI_Comm_size(communicator, &size);
  return size;
}

// Gathers every rank's `local` on rank 0 (concatenated in rank order).
template <typename T>
std::vector<T> gather(const std::vector<T>& local, MPI_Datatype type, MPI_Comm communicator,
                      const char* where) {
  const int ranks = size_of(communicator);
  if (local.size() > static_cast<std::size_t>(INT_MAX)) {
    throw Error("too many particle values on one rank for one MPI gather", where,
                "use more ranks (or extend fluid_state.cpp to gather in pieces)");
  }
  const int count = static_cast<int>(local.size());
  std::vector<int> counts(ranks), offsets(ranks);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, communicator);
  long long total = std::accumulate(counts.begin(), counts.end(), 0LL);
  MPI_Bcast(&total, 1, MPI_LONG_LONG, 0, communicator);
  if (total > INT_MAX) {
    throw Error("the fluid state has more than 2^31 values, too many for one MPI gather", where,
                "extend fluid_state.cpp to gather in pieces");
  }
  std::vector<T> all;
  if (rank_of(communicator) == 0) {
    std::exclusive_scan(counts.begin(), counts.end(), offsets.begin(), 0);
    all.resize(static_cast<std::size_t>(total));
  }
  MPI_Gatherv(local.data(), count, type, all.data(), counts.data(), offsets.data(), type, 0,
              communicator);
  return all;
}

std::string broadcast_bytes(std::string_view bytes, MPI_Comm communicator) {
  unsigned long long size = bytes.size();
  MPI_Bcast(&size, 1, MPI_UNSIGNED_LONG_LONG, 0, communicator);
  std::string copy(size, '\0');
  if (rank_of(communicator) == 0) copy.assign(bytes);
  for (std::size_t at = 0; at < size; at += kChunk) {
    const int count = static_cast<int>(std::min<std::size_t>(kChunk, size - at));
    MPI_Bcast(copy.data() + at, count, MPI_CHAR, 0, communicator);
  }
  return copy;
}

}  // namespace

void share_verdict(const std::string& rank0_problem, MPI_Comm communicator, const char* where,
                   const char* fix) {
  int bad = rank_of(communicator) == 0 && !rank0_problem.empty() ? 1 : 0;
  MPI_Bcast(&bad, 1, MPI_INT, 0, communicator);
  if (bad == 0) return;
  unsigned long long size = rank0_problem.size();
  MPI_Bcast(&size, 1, MPI_UNSIGNED_LONG_LONG, 0, communicator);
  std::string text(size, '\0');
  if (rank_of(communicator) == 0) text = rank0_problem;
  MPI_Bcast(text.data(), static_cast<int>(size), MPI_CHAR, 0, communicator);
  throw Error(text, where, fix);
}

// ---- Capture -----------------------------------------------------------------------------------

std::string capture_fluid_state(LAMMPS_NS::LAMMPS& lammps, MPI_Comm communicator) {
  constexpr const char* kWhere = "capture_fluid_state";
  check_instance(lammps, kWhere);
  auto& atom = *lammps.atom;
  const auto& domain = *lammps.domain;

  std::vector<double> values(static_cast<std::size_t>(std::max(atom.avec->size_restart(), 0)));
  std::vector<long long> tags;
  std::vector<int> lengths;
  std::size_t used = 0;
  unsigned long long dropped = 0;
  for (int i = 0; i < atom.nlocal; ++i) {
    if (outside_fixed_face(domain, atom.x[i])) {
      ++dropped;
      continue;
    }
    const int length = atom.avec->pack_restart(i, values.data() + used);
    used += static_cast<std::size_t>(length);
    tags.push_back(atom.tag[i]);
    lengths.push_back(length);
  }
  values.resize(used);

  const std::vector<long long> all_tags = gather(tags, MPI_LONG_LONG, communicator, kWhere);
  const std::vector<int> all_lengths = gather(lengths, MPI_INT, communicator, kWhere);
  const std::vector<double> all_values = gather(values, MPI_DOUBLE, communicator, kWhere);
  unsigned long long all_dropped = 0;
  MPI_Reduce(&dropped, &all_dropped, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, 0, communicator);

  FluidState state;
  std::string problem;
  if (rank_of(communicator) == 0) {
    std::vector<std::size_t> starts(all_lengths.size());
    std::exclusive_scan(all_lengths.begin(), all_lengths.end(), starts.begin(), std::size_t{0});
    std::vector<std::size_t> order(all_tags.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return all_tags[a] < all_tags[b]; });
    for (std::size_t n = 1; n < order.size() && problem.empty(); ++n) {
      if (all_tags[order[n]] == all_tags[order[n - 1]]) {
        problem = "two particles carry tag " + std::to_string(all_tags[order[n]]);
      }
    }
    state.values.reserve(all_values.size());
    for (std::size_t j : order) {
      const auto length = static_cast<std::size_t>(all_lengths[j]);
      state.records.push_back({all_tags[j], state.values.size(), length});
      state.values.insert(state.values.end(), all_values.begin() + starts[j],
                          all_values.begin() + starts[j] + length);
    }
  }
  share_verdict(problem, communicator, kWhere,
                "LIGGGHTS' particle IDs are inconsistent; report this with the scripts (a bug)");
  if (rank_of(communicator) != 0) return {};

  Header& header = state.header;
  header.dimension = domain.dimension;
  header.atom_style = atom.atom_style;
  header.step = lammps.update->ntimestep;
  header.time_step = lammps.update->atimestep;
  header.time = lammps.update->atime;
  header.record_count = state.records.size();
  header.dropped = all_dropped;
  header.carried = carried_fixes(lammps);
  header.counters = fix_counters(lammps);
  return serialize(state);
}

// ---- Restore -----------------------------------------------------------------------------------

void restore_fluid_state(LAMMPS_NS::LAMMPS& lammps, MPI_Comm communicator, std::string_view bytes) {
  constexpr const char* kWhere = "restore_fluid_state";
  const std::string shared = broadcast_bytes(bytes, communicator);
  // Every rank parses and checks the same bytes against the same scripts: every check below
  // fails on all ranks together, before any particle is touched.
  const FluidState state = parse(shared);
  const Header& header = state.header;
  check_instance(lammps, kWhere);
  auto& atom = *lammps.atom;
  auto& domain = *lammps.domain;
  auto& modify = *lammps.modify;
  auto& update = *lammps.update;

  if (header.atom_style != atom.atom_style) {
    throw Error("the checkpoint holds particles of atom style '" + header.atom_style +
                    "', LIGGGHTS runs atom style '" + std::string(atom.atom_style) + "'",
                kWhere,
                "resume with the scripts the checkpointed run used (atom_style in script 1)");
  }
  if (header.dimension != domain.dimension) {
    throw Error("the checkpoint is " + std::to_string(header.dimension) + "D, LIGGGHTS runs " +
                    std::to_string(domain.dimension) + "D",
                kWhere, "resume with the scripts the checkpointed run used (dimension)");
  }
  const std::vector<CarriedFix> carried = carried_fixes(lammps);
  if (carried != header.carried) {
    auto names = [](const std::vector<CarriedFix>& fixes) {
      std::string text;
      for (const CarriedFix& fix : fixes)
        text += (text.empty() ? "" : ", ") + fix.id + " (" + fix.style + ")";
      return text.empty() ? std::string("none") : text;
    };
    throw Error("the particle records carry per-atom data of the fixes [" + names(header.carried) +
                    "], these scripts define [" + names(carried) + "]",
                kWhere,
                "resume with the scripts the checkpointed run used (same fixes, same order)");
  }
  const std::vector<FixCounter> counters = fix_counters(lammps);
  for (const FixCounter& now : counters) {
    const auto saved = std::find_if(header.counters.begin(), header.counters.end(),
                                    [&](const FixCounter& c) { return c.id == now.id; });
    if (saved == header.counters.end() || saved->every != now.every) {
      throw Error("fix '" + now.id + "' (" + kShepardStyle + ", every " +
                      std::to_string(now.every) + ") " +
                      (saved == header.counters.end()
                           ? std::string("is not in the checkpoint")
                           : "was every " + std::to_string(saved->every) + " in the checkpoint"),
                  kWhere, "resume with the scripts the checkpointed run used");
    }
  }
  if (counters.size() != header.counters.size()) {
    throw Error("the checkpoint has " + std::to_string(header.counters.size()) + " " +
                    kShepardStyle + " fixes, these scripts " + std::to_string(counters.size()),
                kWhere, "resume with the scripts the checkpointed run used");
  }
  if (header.step != update.ntimestep) {
    for (int j = 0; j < modify.nfix; ++j) {
      if (modify.fix[j]->time_depend) {
        throw Error("the step must change from " + std::to_string(update.ntimestep) + " to " +
                        std::to_string(header.step) + " but " + fix_name(*modify.fix[j]) +
                        " depends on the step",
                    kWhere, "define that fix after the restore, or leave it out");
      }
    }
  }
  if (atom.nextra_store != 0) {
    throw Error("per-atom data of a read_restart is still waiting for its fixes", kWhere,
                "do not combine read_restart with restore_fluid_state");
  }
  // The records must have this instance's layout; any rank holding a particle knows it.
  int layout = -1;
  if (atom.nlocal > 0) {
    std::vector<double> scratch(static_cast<std::size_t>(atom.avec->size_restart()));
    layout = atom.avec->pack_restart(0, scratch.data());
  }
  int global_layout = -1;
  MPI_Allreduce(&layout, &global_layout, 1, MPI_INT, MPI_MAX, communicator);
  std::size_t widest = 0;
  for (const Record& record : state.records) {
    widest = std::max(widest, record.length);
    if (global_layout > 0 && record.length != static_cast<std::size_t>(global_layout)) {
      throw Error("the particle record of tag " + std::to_string(record.tag) + " has " +
                      std::to_string(record.length) + " values, this atom style and fixes " +
                      std::to_string(global_layout),
                  kWhere, "resume with the scripts the checkpointed run used");
    }
  }

  // Which records are this rank's; every record must be some rank's.
  std::vector<std::size_t> mine;
  for (std::size_t n = 0; n < state.records.size(); ++n) {
    const Record& record = state.records[n];
    const double* x = state.values.data() + record.offset + 1;
    const std::array<double, 3> p = mapped_into_box(domain, x);
    bool in_box = true, in_sub_domain = true;
    for (int k = 0; k < 3; ++k) {
      in_box = in_box && p[k] >= domain.boxlo[k] && p[k] < domain.boxhi[k];
      in_sub_domain = in_sub_domain && p[k] >= domain.sublo[k] && p[k] < domain.subhi[k];
    }
    if (!in_box) {
      throw Error("the particle of tag " + std::to_string(record.tag) + " lies at (" +
                      format_double(x[0]) + ", " + format_double(x[1]) + ", " +
                      format_double(x[2]) + "), outside the LIGGGHTS box [" +
                      format_double(domain.boxlo[0]) + ", " + format_double(domain.boxhi[0]) +
                      ") x [" + format_double(domain.boxlo[1]) + ", " +
                      format_double(domain.boxhi[1]) + ") x [" + format_double(domain.boxlo[2]) +
                      ", " + format_double(domain.boxhi[2]) + ")",
                  kWhere,
                  "resume with the box of the checkpointed run (region/create_box in "
                  "script 1 and its variables)");
    }
    if (in_sub_domain) mine.push_back(n);
  }
  unsigned long long placed = mine.size(), all_placed = 0;
  MPI_Allreduce(&placed, &all_placed, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, communicator);
  if (all_placed != header.record_count) {
    throw Error("the sub-domains of the ranks take " + std::to_string(all_placed) + " of " +
                    std::to_string(header.record_count) + " particle records",
                kWhere, "report this with the scripts and the rank count (a bug)");
  }

  // ---- From here on the particles are replaced. ----
  if (atom.map_style) atom.map_clear();
  atom.nlocal = 0;
  atom.nghost = 0;
  // AtomVec::unpack_restart leaves the fixes' values in atom->extra (as read_restart does);
  // Fix::unpack_restart takes them from there.
  const bool with_extra = !carried.empty();
  if (with_extra) {
    atom.nextra_store = static_cast<int>(widest);
    lammps.memory->create(atom.extra, std::max(atom.nmax, 1), atom.nextra_store, "atom:extra");
  }
  std::vector<double> buffer;
  for (std::size_t n : mine) {
    const Record& record = state.records[n];
    buffer.assign(state.values.begin() + record.offset,
                  state.values.begin() + record.offset + record.length);
    const int used = atom.avec->unpack_restart(buffer.data());
    const int slot = atom.nlocal - 1;
    // The layout was checked above when any particle existed; this catches the rest.
    if (atom.tag[slot] != record.tag ||
        (!with_extra && static_cast<std::size_t>(used) != record.length)) {
      throw Error("the particle record of tag " + std::to_string(record.tag) +
                      " does not fit atom style '" + std::string(atom.atom_style) +
                      "' (the fluid is now incomplete)",
                  kWhere, "resume with the scripts the checkpointed run used");
    }
    // Derivatives and forces are not state: set-up clears and recomputes them. Clear them here
    // too, so nothing ever depends on what the slot held before.
    atom.f[slot][0] = atom.f[slot][1] = atom.f[slot][2] = 0.0;
    if (atom.drho) atom.drho[slot] = 0.0;
    if (atom.de) atom.de[slot] = 0.0;
  }
  if (with_extra) {
    for (int k = 0; k < atom.nextra_restart; ++k) {
      LAMMPS_NS::Fix& fix = *modify.fix[atom.extra_restart[k]];
      for (int i = 0; i < atom.nlocal; ++i)
        fix.unpack_restart(i, k);
      // As after read_restart: the next set-up must not overwrite these values as if the
      // particles were new (Modify::setup calls set_arrays for just-created fixes otherwise).
      fix.recent_restart = 1;
    }
    lammps.memory->destroy(atom.extra);
    atom.extra = nullptr;
    atom.nextra_store = 0;
  }
  long long local = atom.nlocal, total = 0;
  MPI_Allreduce(&local, &total, 1, MPI_LONG_LONG, MPI_SUM, communicator);
  atom.natoms = total;
  if (atom.map_style) {
    atom.map_init();
    atom.map_set();
  }

  if (header.step != update.ntimestep) update.reset_timestep(header.step);
  update.atime = header.time;
  update.atimestep = header.time_step;
  for (int j = 0; j < modify.nfix; ++j) {
    if (auto* filter = as_shepard_filter(modify.fix[j])) {
      const auto saved = std::find_if(header.counters.begin(), header.counters.end(),
                                      [&](const FixCounter& c) { return c.id == filter->id; });
      filter->*member_pointer(ShepardCounter{}) = saved->ago;
    }
  }
  // Neighbour lists, ghosts and forces refer to the old particles: the next run must set up,
  // even a `run N pre no` (Run::command sets up when first_update is 0).
  update.first_update = 0;
}

// ---- The last step's rates ---------------------------------------------------------------------

namespace {
constexpr char kRatesMagic[8] = {'F', 'S', 'I', 'R', 'A', 'T', 'E', 'S'};
constexpr std::size_t kRateValues = 4;  // f[0..2], drho
}  // namespace

std::string capture_step_rates(LAMMPS_NS::LAMMPS& lammps, MPI_Comm communicator) {
  constexpr const char* kWhere = "capture_step_rates";
  const auto& atom = *lammps.atom;
  std::vector<long long> tags;
  std::vector<double> values;
  for (int i = 0; i < atom.nlocal; ++i) {
    tags.push_back(atom.tag[i]);
    for (int k = 0; k < 3; ++k)
      values.push_back(atom.f[i][k]);
    values.push_back(atom.drho ? atom.drho[i] : 0.0);
  }
  const std::vector<long long> all_tags = gather(tags, MPI_LONG_LONG, communicator, kWhere);
  const std::vector<double> all_values = gather(values, MPI_DOUBLE, communicator, kWhere);
  if (rank_of(communicator) != 0) return {};
  std::vector<std::size_t> order(all_tags.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return all_tags[a] < all_tags[b]; });
  Writer out;
  out.put_raw(kRatesMagic, sizeof kRatesMagic);
  out.put(static_cast<std::uint64_t>(order.size()));
  for (std::size_t j : order) {
    out.put(static_cast<std::int64_t>(all_tags[j]));
    out.put_doubles(all_values.data() + kRateValues * j, kRateValues);
  }
  return out.take();
}

void apply_step_rates(LAMMPS_NS::LAMMPS& lammps, MPI_Comm communicator, std::string_view bytes) {
  constexpr const char* kWhere = "apply_step_rates";
  const std::string shared = broadcast_bytes(bytes, communicator);
  constexpr std::size_t kRecord = sizeof(std::int64_t) + kRateValues * sizeof(double);
  std::uint64_t count = 0;
  const bool framed = shared.size() >= sizeof kRatesMagic + sizeof count &&
                      std::memcmp(shared.data(), kRatesMagic, sizeof kRatesMagic) == 0;
  if (framed) std::memcpy(&count, shared.data() + sizeof kRatesMagic, sizeof count);
  const std::size_t begin = sizeof kRatesMagic + sizeof count;
  auto& atom = *lammps.atom;
  if (!framed || shared.size() != begin + count * kRecord ||
      static_cast<long long>(count) != static_cast<long long>(atom.natoms)) {
    throw Error("the checkpoint's step rates do not fit the fluid (" + std::to_string(count) +
                    " records for " + std::to_string(static_cast<long long>(atom.natoms)) +
                    " particles, " + std::to_string(shared.size()) + " bytes)",
                kWhere, "resume from another checkpoint; this one is damaged or of another run");
  }
  int applied = 0;
  for (std::uint64_t r = 0; r < count; ++r) {
    const char* record = shared.data() + begin + r * kRecord;
    std::int64_t tag = 0;
    double rates[kRateValues];
    std::memcpy(&tag, record, sizeof tag);
    std::memcpy(rates, record + sizeof tag, sizeof rates);
    const int i = atom.map(static_cast<int>(tag));
    if (i < 0 || i >= atom.nlocal) continue;  // another rank's particle (or a ghost here)
    for (int k = 0; k < 3; ++k)
      atom.f[i][k] = rates[k];
    if (atom.drho) atom.drho[i] = rates[3];
    ++applied;
  }
  // Every particle of every rank got its rates.
  int local = atom.nlocal - applied, total = 0;
  MPI_Allreduce(&local, &total, 1, MPI_INT, MPI_SUM, communicator);
  if (total != 0) {
    throw Error(std::to_string(total) + " particle(s) found no rates in the checkpoint", kWhere,
                "resume from another checkpoint; this one is damaged or of another run");
  }
}

}  // namespace fsi::client
