#include "color.hpp"

#include <array>
#include <cstdint>

namespace discreel::scene::detail {
namespace {

std::optional<int> hex_digit(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return std::nullopt;
}

std::optional<std::uint8_t> hex_byte(std::string_view two) {
    const auto high = hex_digit(two[0]);
    const auto low = hex_digit(two[1]);
    if (!high || !low) return std::nullopt;
    return static_cast<std::uint8_t>(*high * 16 + *low);
}

constexpr std::array<Color, 8> palette{{
    {0xf4, 0xd3, 0x5e, 0xff},  // saffron
    {0xe4, 0x57, 0x2e, 0xff},  // vermilion
    {0x17, 0xbe, 0xbb, 0xff},  // teal
    {0x76, 0xb0, 0x41, 0xff},  // leaf green
    {0xee, 0x96, 0x4b, 0xff},  // apricot
    {0x5d, 0x8b, 0xf4, 0xff},  // cornflower
    {0xd6, 0x6b, 0xa0, 0xff},  // orchid
    {0xf2, 0xf2, 0xe6, 0xff},  // ivory
}};

}  // namespace

std::optional<Color> parse_color(std::string_view text) {
    if ((text.size() != 7 && text.size() != 9) || text[0] != '#') return std::nullopt;
    Color color;
    std::uint8_t* channels[] = {&color.r, &color.g, &color.b, &color.a};
    for (std::size_t i = 0; 1 + 2 * i < text.size(); ++i) {
        const auto byte = hex_byte(text.substr(1 + 2 * i, 2));
        if (!byte) return std::nullopt;
        *channels[i] = *byte;
    }
    return color;
}

Color palette_color(std::size_t disc_index) { return palette[disc_index % palette.size()]; }

}  // namespace discreel::scene::detail
