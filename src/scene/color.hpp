#pragma once
// Colours as scene files write them ("#rrggbb", "#rrggbbaa") and the palette for discs that
// name none.
#include <cstddef>
#include <optional>
#include <string_view>

#include "discreel/scene.hpp"

namespace discreel::scene::detail {

// "#rrggbb" (opaque) or "#rrggbbaa", hex digits in either case; nothing else.
std::optional<Color> parse_color(std::string_view text);

// A fixed palette of well-separated, saturated colours that read on the dark default
// background, cycled by disc index.
Color palette_color(std::size_t disc_index);

}  // namespace discreel::scene::detail
