#include "palette_converter.hpp"

#include <algorithm>
#include <utility>

namespace discreel::encode {
namespace {

constexpr std::size_t palette_size = 256;   // GIF's limit
// Levels per channel of the fallback cube: 5^3 = 125 entries, at most 32 units from any
// colour per channel, which leaves 131 entries for the scene's own colours.
constexpr int cube_levels = 5;
constexpr std::size_t cube_entries = std::size_t{cube_levels} * cube_levels * cube_levels;

std::uint32_t pack(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    return (std::uint32_t{r} << 16) | (std::uint32_t{g} << 8) | std::uint32_t{b};
}
std::uint32_t pack(const Rgb& c) { return pack(c[0], c[1], c[2]); }
Rgb unpack(std::uint32_t v) {
    return {static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 8),
            static_cast<std::uint8_t>(v)};
}

}  // namespace

PaletteConverter::PaletteConverter(std::vector<Rgb> key_colours)
    : key_colours_(std::move(key_colours)) {}

void PaletteConverter::build_palette(const ImageView& first_frame) {
    std::vector<std::uint32_t> present;   // packed, in palette order
    const auto add = [&](std::uint32_t colour) {
        if (present.size() < palette_size &&
            std::find(present.begin(), present.end(), colour) == present.end()) {
            present.push_back(colour);
        }
    };
    for (const Rgb& colour : key_colours_) {
        add(pack(colour));
    }

    std::vector<std::uint32_t> pixels;
    pixels.reserve(first_frame.rgba.size() / 4);
    for (std::size_t i = 0; i + 3 < first_frame.rgba.size(); i += 4) {
        pixels.push_back(pack(first_frame.rgba[i], first_frame.rgba[i + 1], first_frame.rgba[i + 2]));
    }
    std::sort(pixels.begin(), pixels.end());
    std::vector<std::pair<std::size_t, std::uint32_t>> counted;   // (count, colour)
    for (std::size_t i = 0; i < pixels.size();) {
        std::size_t j = i;
        while (j < pixels.size() && pixels[j] == pixels[i]) ++j;
        counted.emplace_back(j - i, pixels[i]);
        i = j;
    }
    std::stable_sort(counted.begin(), counted.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });

    std::vector<std::uint32_t> all = present;
    for (const auto& entry : counted) {
        if (std::find(present.begin(), present.end(), entry.second) == present.end()) {
            all.push_back(entry.second);
            if (all.size() > palette_size) break;
        }
    }
    if (all.size() > palette_size) {
        // Too many colours: the most frequent ones (flat areas, common edge blends) first, then
        // a coarse colour cube so that no colour is far from an entry, then more frequent ones.
        for (const auto& entry : counted) {
            if (present.size() >= palette_size - cube_entries) break;
            add(entry.second);
        }
        for (int r = 0; r < cube_levels; ++r) {
            for (int g = 0; g < cube_levels; ++g) {
                for (int b = 0; b < cube_levels; ++b) {
                    const auto level = [](int i) {
                        return static_cast<std::uint8_t>(i * 255 / (cube_levels - 1));
                    };
                    add(pack(level(r), level(g), level(b)));
                }
            }
        }
    }
    for (const auto& entry : counted) {
        add(entry.second);
    }

    palette_.clear();
    for (const std::uint32_t colour : present) {
        palette_.push_back(unpack(colour));
    }
    lookup_.assign(std::size_t{1} << 24, 0);
}

std::uint8_t PaletteConverter::index_of(std::uint32_t rgb) {
    std::uint16_t& known = lookup_[rgb];
    if (known == 0) {
        const Rgb colour = unpack(rgb);
        int best_distance = 1 << 30;
        std::size_t best = 0;
        for (std::size_t i = 0; i < palette_.size(); ++i) {
            int distance = 0;
            for (int c = 0; c < 3; ++c) {
                const int d = int{colour[c]} - int{palette_[i][c]};
                distance += d * d;
            }
            if (distance < best_distance) {
                best_distance = distance;
                best = i;
            }
        }
        known = static_cast<std::uint16_t>(best + 1);
    }
    return static_cast<std::uint8_t>(known - 1);
}

void PaletteConverter::convert(const ImageView& frame, AVFrame& output) {
    if (palette_.empty()) {
        build_palette(frame);
    }
    // AV_PIX_FMT_PAL8: data[1] holds 256 native-endian 0xAARRGGBB entries. Every entry is
    // opaque, so the GIF encoder never picks one as the transparent colour.
    auto* entries = reinterpret_cast<std::uint32_t*>(output.data[1]);
    for (std::size_t i = 0; i < palette_size; ++i) {
        entries[i] = 0xFF000000u | (i < palette_.size() ? pack(palette_[i]) : 0u);
    }
    for (int y = 0; y < frame.height; ++y) {
        const std::uint8_t* source = frame.rgba.data() + std::size_t{4} * static_cast<std::size_t>(y) *
                                                             static_cast<std::size_t>(frame.width);
        std::uint8_t* row = output.data[0] + static_cast<std::ptrdiff_t>(y) * output.linesize[0];
        for (int x = 0; x < frame.width; ++x, source += 4) {
            row[x] = index_of(pack(source[0], source[1], source[2]));
        }
    }
}

}  // namespace discreel::encode
