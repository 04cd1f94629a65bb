#include "fsi/output/checkpoint_store.hpp"

#include <openssl/evp.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <system_error>

#include "fsi/common/error.hpp"
#include "fsi/common/utc_time.hpp"
#include "fsi/output/atomic_file.hpp"

namespace fsi::output {

namespace fs = std::filesystem;

namespace {

constexpr const char* kManifestName = "checkpoint.json";
constexpr const char* kPartialSuffix = ".partial";
constexpr const char* kFormatName = "fsi-checkpoint";

// The step of a folder named step-N (complete) or step-N.partial; nullopt for other names.
std::optional<std::uint64_t> step_of(const std::string& name, bool& partial) {
  partial = name.size() > std::char_traits<char>::length(kPartialSuffix) &&
            name.ends_with(kPartialSuffix);
  const std::string stem =
      partial ? name.substr(0, name.size() - std::char_traits<char>::length(kPartialSuffix)) : name;
  if (!stem.starts_with("step-") || stem.size() == 5) return std::nullopt;
  std::uint64_t step = 0;
  for (std::size_t i = 5; i < stem.size(); ++i) {
    if (stem[i] < '0' || stem[i] > '9') return std::nullopt;
    step = step * 10 + static_cast<std::uint64_t>(stem[i] - '0');
  }
  return step;
}

std::optional<std::string> read_whole(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The manifest of `folder`, or the reason it cannot be trusted.
std::optional<Checkpoint> read_manifest(const fs::path& folder, std::string& problem) {
  const auto text = read_whole(folder / kManifestName);
  if (!text) {
    problem = std::string("no ") + kManifestName + " (written last: the checkpoint is incomplete)";
    return std::nullopt;
  }
  try {
    const nlohmann::json json = nlohmann::json::parse(*text);
    if (json.value("format", "") != kFormatName) {
      problem = std::string(kManifestName) + " is not an fsi checkpoint manifest";
      return std::nullopt;
    }
    const int version = json.at("format_version").get<int>();
    if (version != kCheckpointFormatVersion) {
      problem = "checkpoint format version " + std::to_string(version) + ", this program reads " +
                std::to_string(kCheckpointFormatVersion) +
                " (resume it with the release that wrote it)";
      return std::nullopt;
    }
    Checkpoint checkpoint;
    checkpoint.folder = folder;
    checkpoint.step = json.at("step").get<std::uint64_t>();
    checkpoint.time = json.at("time").get<double>();
    checkpoint.written_utc = json.value("written_utc", "");
    for (const auto& file : json.at("files")) {
      checkpoint.files.push_back({file.at("name").get<std::string>(),
                                  file.at("bytes").get<std::uint64_t>(),
                                  file.at("sha256").get<std::string>()});
    }
    return checkpoint;
  } catch (const std::exception& failure) {
    problem = std::string(kManifestName) + " cannot be read: " + failure.what();
    return std::nullopt;
  }
}

// Why `file` of `checkpoint` does not match its manifest entry; empty when it does.
std::string mismatch(const Checkpoint& checkpoint, const CheckpointFile& file,
                     std::string* contents = nullptr) {
  auto bytes = read_whole(checkpoint.folder / file.name);
  if (!bytes) return file.name + " is missing";
  if (bytes->size() != file.bytes) {
    return file.name + " holds " + std::to_string(bytes->size()) + " bytes, the manifest says " +
           std::to_string(file.bytes);
  }
  if (sha256_hex(*bytes) != file.sha256)
    return file.name + " does not match its SHA-256 in the manifest (changed or damaged)";
  if (contents) *contents = std::move(*bytes);
  return {};
}

Error store_error(const std::string& what, const fs::path& where, const std::error_code& error) {
  return Error(what + " " + where.string() + ": " + error.message(), "checkpoint store",
               "make the --output folder writable and give its disk room for two checkpoints "
               "(df -h), or set Output.checkpoint_every_steps = 0 to run without them");
}

}  // namespace

std::string checkpoint_folder_name(std::uint64_t step) {
  char name[40];
  std::snprintf(name, sizeof name, "step-%09llu", static_cast<unsigned long long>(step));
  return name;
}

std::string sha256_hex(std::string_view bytes) {
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int length = 0;
  if (EVP_Digest(bytes.data(), bytes.size(), digest.data(), &length, EVP_sha256(), nullptr) != 1)
    throw Error("SHA-256 failed", "OpenSSL", "check the OpenSSL installation (libssl3)");
  static constexpr char kHex[] = "0123456789abcdef";
  std::string hex;
  hex.reserve(2 * length);
  for (unsigned int i = 0; i < length; ++i) {
    hex.push_back(kHex[digest[i] >> 4]);
    hex.push_back(kHex[digest[i] & 15]);
  }
  return hex;
}

CheckpointStore::CheckpointStore(fs::path root, int keep) : root_(std::move(root)), keep_(keep) {
  if (keep_ < 1) {
    throw Error("keeping " + std::to_string(keep) + " checkpoints", "checkpoint store",
                "keep at least 1");
  }
}

void CheckpointStore::begin(std::uint64_t step) {
  const fs::path folder = root_ / (checkpoint_folder_name(step) + kPartialSuffix);
  std::error_code error;
  fs::create_directories(root_, error);
  if (error) throw store_error("cannot create the checkpoint folder", root_, error);
  fs::remove_all(folder, error);
  if (error) throw store_error("cannot remove the leftover", folder, error);
  fs::create_directory(folder, error);
  if (error) throw store_error("cannot create", folder, error);
  pending_ = step;
  pending_files_.clear();
}

void CheckpointStore::add(const std::string& name, std::string_view bytes) {
  if (!pending_) throw Error("a checkpoint file outside a checkpoint", name, "call begin() first");
  if (name.empty() || name.find('/') != std::string::npos || name == kManifestName) {
    throw Error("checkpoint file name '" + name + "'", "checkpoint store",
                std::string("use a plain file name other than ") + kManifestName);
  }
  const fs::path folder = root_ / (checkpoint_folder_name(*pending_) + kPartialSuffix);
  write_file_atomically(folder / name, bytes, Durability::MachineCrash);
  pending_files_.push_back(name);
}

Checkpoint CheckpointStore::commit(double time) {
  if (!pending_) throw Error("committing no checkpoint", "checkpoint store", "call begin() first");
  const std::uint64_t step = *pending_;
  const fs::path partial = root_ / (checkpoint_folder_name(step) + kPartialSuffix);
  const fs::path complete = root_ / checkpoint_folder_name(step);
  Checkpoint checkpoint;
  checkpoint.folder = complete;
  checkpoint.step = step;
  checkpoint.time = time;
  checkpoint.written_utc = utc_now();
  nlohmann::json files = nlohmann::json::array();
  for (const std::string& name : pending_files_) {
    const auto bytes = read_whole(partial / name);
    if (!bytes) {
      throw Error("cannot read back " + (partial / name).string(), "checkpoint store",
                  "check the disk of the --output folder");
    }
    CheckpointFile file{name, bytes->size(), sha256_hex(*bytes)};
    files.push_back({{"name", file.name}, {"bytes", file.bytes}, {"sha256", file.sha256}});
    checkpoint.files.push_back(std::move(file));
  }
  char time_text[40];
  std::snprintf(time_text, sizeof time_text, "%.17g", time);
  const nlohmann::json manifest = {
      {"format", kFormatName},  {"format_version", kCheckpointFormatVersion},
      {"step", step},           {"time", time},
      {"time_text", time_text}, {"written_utc", checkpoint.written_utc},
      {"files", files}};
  write_file_atomically(partial / kManifestName, manifest.dump(2) + "\n", Durability::MachineCrash);
  sync_folder(partial);
  std::error_code error;
  fs::remove_all(complete, error);  // a checkpoint of the same step from before a rollback
  fs::rename(partial, complete, error);
  if (error) throw store_error("cannot rename the checkpoint to", complete, error);
  sync_folder(root_);
  pending_.reset();
  pending_files_.clear();

  // Keep the newest `keep_` complete checkpoints; remove older ones and stale partial folders.
  std::vector<std::pair<std::uint64_t, fs::path>> complete_folders;
  for (const auto& entry : fs::directory_iterator(root_, error)) {
    bool is_partial = false;
    const auto entry_step = step_of(entry.path().filename().string(), is_partial);
    if (!entry_step || !entry.is_directory()) continue;
    if (is_partial) {
      fs::remove_all(entry.path(), error);
    } else {
      complete_folders.emplace_back(*entry_step, entry.path());
    }
  }
  std::sort(complete_folders.begin(), complete_folders.end());
  const std::size_t keep = static_cast<std::size_t>(keep_);
  for (std::size_t i = 0; i + keep < complete_folders.size(); ++i)
    fs::remove_all(complete_folders[i].second, error);
  sync_folder(root_);
  return checkpoint;
}

void CheckpointStore::abandon() noexcept {
  if (!pending_) return;
  std::error_code error;
  fs::remove_all(root_ / (checkpoint_folder_name(*pending_) + kPartialSuffix), error);
  pending_.reset();
  pending_files_.clear();
}

std::vector<Checkpoint> CheckpointStore::list(std::vector<std::string>* skipped) const {
  std::vector<Checkpoint> found;
  std::error_code error;
  if (!fs::is_directory(root_, error)) return found;
  for (const auto& entry : fs::directory_iterator(root_, error)) {
    bool is_partial = false;
    const std::string name = entry.path().filename().string();
    const auto step = step_of(name, is_partial);
    if (!step || !entry.is_directory()) continue;
    if (is_partial) {
      if (skipped) skipped->push_back(name + ": unfinished (the run stopped while writing it)");
      continue;
    }
    std::string problem;
    auto checkpoint = read_manifest(entry.path(), problem);
    if (!checkpoint) {
      if (skipped) skipped->push_back(name + ": " + problem);
      continue;
    }
    if (checkpoint->step != *step) {
      if (skipped) {
        skipped->push_back(name + ": its manifest says step " + std::to_string(checkpoint->step));
      }
      continue;
    }
    found.push_back(std::move(*checkpoint));
  }
  std::sort(found.begin(), found.end(),
            [](const Checkpoint& a, const Checkpoint& b) { return a.step < b.step; });
  return found;
}

std::optional<Checkpoint> CheckpointStore::newest_valid(std::vector<std::string>* skipped) const {
  std::vector<Checkpoint> found = list(skipped);
  for (auto it = found.rbegin(); it != found.rend(); ++it) {
    std::string problem;
    for (const CheckpointFile& file : it->files) {
      problem = mismatch(*it, file);
      if (!problem.empty()) break;
    }
    if (problem.empty()) return *it;
    if (skipped) skipped->push_back(it->folder.filename().string() + ": " + problem);
  }
  return std::nullopt;
}

std::string read_checkpoint_file(const Checkpoint& checkpoint, const std::string& name) {
  const auto entry = std::find_if(checkpoint.files.begin(), checkpoint.files.end(),
                                  [&](const CheckpointFile& file) { return file.name == name; });
  if (entry == checkpoint.files.end()) {
    throw Error("the checkpoint holds no file " + name, checkpoint.folder.string(),
                "resume with the release and scene that wrote it");
  }
  std::string contents;
  const std::string problem = mismatch(checkpoint, *entry, &contents);
  if (!problem.empty()) {
    throw Error(problem, checkpoint.folder.string(),
                "resume from an older checkpoint: move this folder away and resume again");
  }
  return contents;
}

}  // namespace fsi::output
