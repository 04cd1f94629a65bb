#pragma once
// The scene's Assembly block (internal to the scene builder): its declaration, the driving
// coordinates it names, and the initial assembly of the built model (fsi/mbd/assembly.hpp).

#include <optional>
#include <vector>

#include "fsi/mbd/assembly.hpp"
#include "fsi/mbd/model.hpp"
#include "fsi/scene/problem.hpp"
#include "fsi/scene/schema.hpp"

namespace fsi::scene::detail {

BlockSpec assembly_block_spec();

struct AssemblyRequest {
  mbd::AssemblyOptions options;
  SourceLocation block;  // where a loop that cannot close is reported
};

// The request of an enabled Assembly block of a built model; nullopt when the block is absent or
// switched off. Unknown bodies and coordinates in `driving` are problems at the key.
std::optional<AssemblyRequest> assembly_request(const View& root, const mbd::Model& model,
                                                std::vector<Problem>& problems);

// Assembles the model's initial configuration and installs it in the model (throws fsi::Error at
// the block when the constraints cannot be met).
mbd::AssemblyReport assemble_initial_configuration(mbd::Model& model,
                                                   const AssemblyRequest& request);

}  // namespace fsi::scene::detail
