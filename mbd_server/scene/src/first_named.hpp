#pragma once
// The look-up by name that the scene's trees share: a file's blocks, a schema's parameters and
// blocks.

#include <algorithm>
#include <string_view>
#include <vector>

namespace fsi::scene::detail {

// The first of `items` whose `name_member` is `name`; nullptr if none is.
template <class Item, class Name>
const Item* first_named(const std::vector<Item>& items, std::string_view name,
                        Name Item::*name_member) {
  const auto found =
      std::ranges::find_if(items, [&](const Item& item) { return item.*name_member == name; });
  return found == items.end() ? nullptr : &*found;
}

}  // namespace fsi::scene::detail
