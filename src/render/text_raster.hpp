#pragma once
// TextLabel drawn with a TrueType font through FreeType onto a frame read back from GL: each
// glyph rendered once per pixel size (8-bit anti-aliased coverage) and cached, then blended over
// the image in straight alpha, as the GL pass leaves it. On the CPU, after the frame: text is a
// few thousand pixels a line, and the glyph bitmaps need no texture of their own.
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "discreel/expected.hpp"
#include "discreel/render.hpp"

namespace discreel::render {

class FontRaster {
public:
    // The font at `path`; fails with a message that names the file and the Debian package.
    static Expected<FontRaster> open(const std::string& path);
    ~FontRaster();
    FontRaster(FontRaster&&) noexcept;
    FontRaster& operator=(FontRaster&&) noexcept;
    FontRaster(const FontRaster&) = delete;
    FontRaster& operator=(const FontRaster&) = delete;

    // Blends `label` over `rgba` (width x height pixels, top row first, straight alpha), the
    // world placed by `camera`.
    void draw(const TextLabel& label, const Camera& camera, std::span<std::uint8_t> rgba,
              int width, int height);

private:
    // The glyphs of `lines` in `color`, each line's pen starting at its pixel (x, baseline).
    void blend_lines(const std::vector<std::u32string>& lines, const std::vector<double>& pens,
                     const std::vector<int>& baselines, int pixels, const Rgba& color,
                     std::span<std::uint8_t> rgba, int width, int height);
    // A level `layer` (w x h, straight alpha) turned by `angle` about its point (lx, ly) and
    // blended over the frame with that point at (ax, ay).
    static void turn_onto(std::span<const std::uint8_t> layer, int w, int h, double lx, double ly,
                          double angle, double ax, double ay, std::span<std::uint8_t> rgba,
                          int width, int height);
    struct Face;
    struct Glyph {
        int left = 0, top = 0;          // pixels from the pen to the bitmap's left and top
        int width = 0, rows = 0;
        double advance = 0;             // pixels
        std::vector<std::uint8_t> coverage;   // rows x width
    };
    explicit FontRaster(std::unique_ptr<Face> face);
    const Glyph& glyph(char32_t code, int pixels);
    double line_width(const std::u32string& line, int pixels);

    std::unique_ptr<Face> face_;
    std::map<std::pair<char32_t, int>, Glyph> cache_;
};

}  // namespace discreel::render
