#pragma once
// Colours as scene files write them ("#rgb", "#rrggbb", "#rrggbbaa", CSS names) and the
// palette for discs that name none.
#include <cstddef>
#include <optional>
#include <span>
#include <string_view>

#include "discreel/scene.hpp"

namespace discreel::scene::detail {

// "#rgb", "#rrggbb" (opaque) or "#rrggbbaa", hex digits in either case, or a CSS colour name
// in any case ("steelblue", "SteelBlue"); nothing else.
std::optional<Color> parse_color(std::string_view text);
// A CSS colour name's colour, in any case.
std::optional<Color> named_color(std::string_view name);
// The CSS colour names, sorted (for "did you mean").
std::span<const std::string_view> color_names();

// A fixed palette of well-separated, saturated colours that read on the dark default
// background, cycled by disc index.
Color palette_color(std::size_t disc_index);

}  // namespace discreel::scene::detail
