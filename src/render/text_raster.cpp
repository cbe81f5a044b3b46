#include "text_raster.hpp"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <cmath>

namespace discreel::render {
namespace {

// Sizes beyond these say nothing more on screen and cost memory in the glyph cache.
constexpr int kSmallestPixels = 4, kLargestPixels = 512;
constexpr double kLineHeight = 1.2;   // ems from one line's baseline to the next

// UTF-8 to code points, line by line; a byte that starts no valid sequence is U+FFFD.
std::vector<std::u32string> lines_of(const std::string& text) {
    std::vector<std::u32string> lines(1);
    for (std::size_t i = 0; i < text.size();) {
        const auto byte = static_cast<unsigned char>(text[i]);
        const int extra = byte < 0x80 ? 0 : (byte >> 5) == 6 ? 1 : (byte >> 4) == 14 ? 2
                                                                  : (byte >> 3) == 30 ? 3 : -1;
        char32_t code = extra == 0 ? byte : extra == 1 ? byte & 0x1f : extra == 2 ? byte & 0x0f
                                                                                  : byte & 0x07;
        bool valid = extra >= 0 && i + static_cast<std::size_t>(extra) < text.size() + 0;
        for (int k = 1; valid && k <= extra; ++k) {
            const auto next = static_cast<unsigned char>(text[i + static_cast<std::size_t>(k)]);
            valid = (next >> 6) == 2;
            code = (code << 6) | (next & 0x3f);
        }
        i += valid ? static_cast<std::size_t>(extra) + 1 : 1;
        if (!valid) code = 0xfffd;
        if (code == '\n') {
            lines.emplace_back();
        } else {
            lines.back().push_back(code);
        }
    }
    return lines;
}

std::uint8_t to_byte(double v) {
    return static_cast<std::uint8_t>(std::clamp(std::lround(v * 255.0), 0L, 255L));
}

}  // namespace

struct FontRaster::Face {
    FT_Library library = nullptr;
    FT_Face face = nullptr;
    ~Face() {
        if (face != nullptr) FT_Done_Face(face);
        if (library != nullptr) FT_Done_FreeType(library);
    }
};

Expected<FontRaster> FontRaster::open(const std::string& path) {
    auto face = std::make_unique<Face>();
    if (FT_Init_FreeType(&face->library) != 0) return Error{"FreeType did not start"};
    if (FT_New_Face(face->library, path.c_str(), 0, &face->face) != 0) {
        return Error{"text needs the font " + path +
                     ", which could not be read (Debian package fonts-dejavu-core)"};
    }
    return FontRaster(std::move(face));
}

FontRaster::FontRaster(std::unique_ptr<Face> face) : face_(std::move(face)) {}
FontRaster::~FontRaster() = default;
FontRaster::FontRaster(FontRaster&&) noexcept = default;
FontRaster& FontRaster::operator=(FontRaster&&) noexcept = default;

const FontRaster::Glyph& FontRaster::glyph(char32_t code, int pixels) {
    const auto key = std::make_pair(code, pixels);
    if (const auto it = cache_.find(key); it != cache_.end()) return it->second;
    Glyph g;
    FT_Face face = face_->face;
    if (FT_Set_Pixel_Sizes(face, 0, static_cast<FT_UInt>(pixels)) == 0 &&
        FT_Load_Char(face, code, FT_LOAD_RENDER) == 0) {
        const FT_GlyphSlot slot = face->glyph;
        const FT_Bitmap& bitmap = slot->bitmap;
        g.left = slot->bitmap_left;
        g.top = slot->bitmap_top;
        g.width = static_cast<int>(bitmap.width);
        g.rows = static_cast<int>(bitmap.rows);
        g.advance = static_cast<double>(slot->advance.x) / 64.0;
        g.coverage.resize(static_cast<std::size_t>(g.width) * static_cast<std::size_t>(g.rows));
        for (int r = 0; r < g.rows; ++r) {
            const unsigned char* row = bitmap.buffer + static_cast<std::ptrdiff_t>(r) * bitmap.pitch;
            std::copy(row, row + g.width,
                      g.coverage.begin() + static_cast<std::ptrdiff_t>(r) * g.width);
        }
    }
    return cache_.emplace(key, std::move(g)).first->second;
}

double FontRaster::line_width(const std::u32string& line, int pixels) {
    double width = 0;
    for (const char32_t c : line) width += glyph(c, pixels).advance;
    return width;
}

void FontRaster::draw(const TextLabel& label, const Camera& camera, std::span<std::uint8_t> rgba,
                      int width, int height) {
    const double pixels_per_metre = height / camera.height;
    const double em = label.world ? label.size * pixels_per_metre : label.size * height;
    if (!(em >= kSmallestPixels)) return;   // too small to read (or not a number)
    const int pixels = std::min(static_cast<int>(std::lround(em)), kLargestPixels);
    // The anchor point, in pixels from the top left.
    const double ax = label.world ? width / 2.0 + (label.x - camera.center_x) * pixels_per_metre
                                  : label.x * width;
    const double ay = label.world ? height / 2.0 - (label.y - camera.center_y) * pixels_per_metre
                                  : label.y * height;
    const std::vector<std::u32string> lines = lines_of(label.text);
    std::vector<double> widths;
    double box_width = 0;
    for (const std::u32string& line : lines) {
        widths.push_back(line_width(line, pixels));
        box_width = std::max(box_width, widths.back());
    }
    const FT_Size_Metrics& metrics = face_->face->size->metrics;
    const double ascender = static_cast<double>(metrics.ascender) / 64.0;
    const double descender = -static_cast<double>(metrics.descender) / 64.0;
    const double line_height = kLineHeight * pixels;
    const double box_height = (static_cast<double>(lines.size()) - 1) * line_height + ascender +
                              descender;
    const int column = static_cast<int>(label.anchor) % 3, row = static_cast<int>(label.anchor) / 3;
    const int halo = label.outline ? std::max(1, static_cast<int>(std::lround(pixels / 12.0))) : 0;
    if (label.angle != 0 && std::isfinite(label.angle)) {
        // Turned: drawn level into a layer of its own, then turned onto the frame.
        const int margin = halo + 2;
        const int w = static_cast<int>(std::ceil(box_width)) + 2 * margin;
        const int h = static_cast<int>(std::ceil(box_height)) + 2 * margin;
        const double lx = margin + box_width * column / 2.0, ly = margin + box_height * row / 2.0;
        TextLabel level = label;
        level.angle = 0;
        level.world = false;
        level.x = lx / w;
        level.y = ly / h;
        level.size = static_cast<double>(pixels) / h;
        std::vector<std::uint8_t> layer(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4, 0);
        draw(level, camera, layer, w, h);
        turn_onto(layer, w, h, lx, ly, label.angle, ax, ay, rgba, width, height);
        return;
    }
    const double left = ax - box_width * column / 2.0;
    const double top = ay - box_height * row / 2.0;
    std::vector<double> pens;
    std::vector<int> baselines;
    for (std::size_t l = 0; l < lines.size(); ++l) {
        // Each line centred in the box when the anchor is, else flush with its side.
        pens.push_back(std::round(left + (box_width - widths[l]) * column / 2.0));
        baselines.push_back(static_cast<int>(
            std::lround(top + ascender + static_cast<double>(l) * line_height)));
    }
    if (label.outline) {
        const int r = halo;
        for (const auto& [dx, dy] : {std::pair{-r, 0}, std::pair{r, 0}, std::pair{0, -r},
                                     std::pair{0, r}, std::pair{-r, -r}, std::pair{r, r},
                                     std::pair{-r, r}, std::pair{r, -r}}) {
            std::vector<double> moved = pens;
            std::vector<int> lowered = baselines;
            for (double& p : moved) p += dx;
            for (int& b : lowered) b += dy;
            blend_lines(lines, moved, lowered, pixels, *label.outline, rgba, width, height);
        }
    }
    blend_lines(lines, pens, baselines, pixels, label.color, rgba, width, height);
}

void FontRaster::turn_onto(std::span<const std::uint8_t> layer, int w, int h, double lx,
                           double ly, double angle, double ax, double ay,
                           std::span<std::uint8_t> rgba, int width, int height) {
    // Frame pixel centres within the layer's reach of the anchor, each mapped back into the
    // layer (turned by -angle; on screen y points down, so a counter-clockwise turn is x' = u
    // cos + v sin, y' = -u sin + v cos) and sampled bilinearly, premultiplied.
    const double c = std::cos(angle), s = std::sin(angle);
    const double reach = std::hypot(std::max(lx, w - lx), std::max(ly, h - ly)) + 1;
    const int x0 = std::max(0, static_cast<int>(std::floor(ax - reach)));
    const int x1 = std::min(width - 1, static_cast<int>(std::ceil(ax + reach)));
    const int y0 = std::max(0, static_cast<int>(std::floor(ay - reach)));
    const int y1 = std::min(height - 1, static_cast<int>(std::ceil(ay + reach)));
    const auto texel = [&](int x, int y, int ch) -> double {
        if (x < 0 || y < 0 || x >= w || y >= h) return 0;
        const std::uint8_t* t = &layer[(static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
                                        static_cast<std::size_t>(x)) * 4];
        const double a = t[3] / 255.0;
        return ch == 3 ? a : t[ch] / 255.0 * a;
    };
    for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
            const double fx = x + 0.5 - ax, fy = y + 0.5 - ay;
            const double u = fx * c - fy * s + lx - 0.5, v = fx * s + fy * c + ly - 0.5;
            const int iu = static_cast<int>(std::floor(u)), iv = static_cast<int>(std::floor(v));
            if (iu < -1 || iv < -1 || iu >= w || iv >= h) continue;
            const double du = u - iu, dv = v - iv;
            double src[4];
            for (int ch = 0; ch < 4; ++ch) {
                src[ch] = (texel(iu, iv, ch) * (1 - du) + texel(iu + 1, iv, ch) * du) * (1 - dv) +
                          (texel(iu, iv + 1, ch) * (1 - du) + texel(iu + 1, iv + 1, ch) * du) * dv;
            }
            if (src[3] <= 0) continue;
            std::uint8_t* p = &rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                     static_cast<std::size_t>(x)) * 4];
            // Premultiplied "over", back to straight alpha.
            const double under = p[3] / 255.0;
            const double out = src[3] + under * (1 - src[3]);
            for (int ch = 0; ch < 3; ++ch) {
                p[ch] = to_byte((src[ch] + p[ch] / 255.0 * under * (1 - src[3])) / out);
            }
            p[3] = to_byte(out);
        }
    }
}

void FontRaster::blend_lines(const std::vector<std::u32string>& lines,
                             const std::vector<double>& pens, const std::vector<int>& baselines,
                             int pixels, const Rgba& color, std::span<std::uint8_t> rgba,
                             int width, int height) {
    const double alpha = std::clamp(static_cast<double>(color.a), 0.0, 1.0);
    const double src[3] = {color.r, color.g, color.b};
    const unsigned alpha8 = to_byte(alpha);
    const unsigned src8[3] = {to_byte(src[0]), to_byte(src[1]), to_byte(src[2])};
    for (std::size_t l = 0; l < lines.size(); ++l) {
        double pen = pens[l];
        const int baseline = baselines[l];
        for (const char32_t c : lines[l]) {
            const Glyph& g = glyph(c, pixels);
            const int x0 = static_cast<int>(pen) + g.left, y0 = baseline - g.top;
            for (int r = 0; r < g.rows; ++r) {
                const int y = y0 + r;
                if (y < 0 || y >= height) continue;
                for (int k = 0; k < g.width; ++k) {
                    const int x = x0 + k;
                    if (x < 0 || x >= width) continue;
                    const unsigned cover =
                        g.coverage[static_cast<std::size_t>(r) * static_cast<std::size_t>(g.width) +
                                   static_cast<std::size_t>(k)];
                    const unsigned a8 = (cover * alpha8 + 127) / 255;
                    if (a8 == 0) continue;
                    std::uint8_t* p =
                        &rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                               static_cast<std::size_t>(x)) * 4];
                    if (p[3] == 255) {
                        // Over an opaque pixel (every frame but a transparent one's): in bytes.
                        for (int ch = 0; ch < 3; ++ch) {
                            p[ch] = static_cast<std::uint8_t>(
                                (src8[ch] * a8 + p[ch] * (255 - a8) + 127) / 255);
                        }
                        continue;
                    }
                    // Straight alpha "over": the text's colour over what is there.
                    const double a = a8 / 255.0;
                    const double under = p[3] / 255.0;
                    const double out = a + under * (1 - a);
                    for (int ch = 0; ch < 3; ++ch) {
                        const double d = p[ch] / 255.0;
                        p[ch] = to_byte((src[ch] * a + d * under * (1 - a)) / out);
                    }
                    p[3] = to_byte(out);
                }
            }
            pen += g.advance;
        }
    }
}

}  // namespace discreel::render
