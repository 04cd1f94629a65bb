// The registry of element families: family_list.inc, read twice, declares each family and lists
// it, so that a new family is one line there.

#include "scene_builder.hpp"

namespace fsi::scene::detail {

#define FSI_SCENE_FAMILY(family) ElementFamily family##_family();
#include "family_list.inc"
#undef FSI_SCENE_FAMILY

const std::vector<ElementFamily>& element_families() {
  static const std::vector<ElementFamily> families = {
#define FSI_SCENE_FAMILY(family) family##_family(),
#include "family_list.inc"
#undef FSI_SCENE_FAMILY
  };
  return families;
}

}  // namespace fsi::scene::detail
