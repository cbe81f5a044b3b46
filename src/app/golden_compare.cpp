#include "golden_compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace discreel::golden {
namespace {

// The YIQ distance of black from white: the largest a pair of opaque colours can be apart.
// Distances are divided by it so thresholds read as fractions of that.
constexpr double kMaxYiqDelta = 35215.0;
// How much of the golden shows through in the diff image: enough to recognise the scene, faint
// enough that red and yellow marks stand out.
constexpr double kDiffBackdropOpacity = 0.25;

struct Rgb {
    double r, g, b;
};

// Translucent pixels are judged as they would look on a white page.
Rgb on_white(const std::uint8_t* p) {
    const double a = p[3] / 255.0;
    return {255 + (p[0] - 255) * a, 255 + (p[1] - 255) * a, 255 + (p[2] - 255) * a};
}

double luma(const Rgb& c) { return c.r * 0.29889531 + c.g * 0.58662247 + c.b * 0.11448223; }
double in_phase(const Rgb& c) { return c.r * 0.59597799 - c.g * 0.27417610 - c.b * 0.32180189; }
double quadrature(const Rgb& c) { return c.r * 0.21147017 - c.g * 0.52261711 + c.b * 0.31114694; }

// Squared YIQ distance, weighted as in "Measuring perceived color difference using YIQ NTSC
// transmission color space in mobile applications" (Kotsarenko and Ramos, 2010).
double yiq_delta(const std::uint8_t* a, const std::uint8_t* b) {
    if (std::memcmp(a, b, 4) == 0) return 0;
    const Rgb ca = on_white(a), cb = on_white(b);
    const double y = luma(ca) - luma(cb);
    const double i = in_phase(ca) - in_phase(cb);
    const double q = quadrature(ca) - quadrature(cb);
    return 0.5053 * y * y + 0.299 * i * i + 0.1957 * q * q;
}

class Pixels {
public:
    explicit Pixels(const ImageView& image) : image_(image) {}
    const std::uint8_t* at(int x, int y) const {
        return image_.rgba.data() + 4 * (static_cast<std::size_t>(y) * image_.width + x);
    }
    int width() const { return image_.width; }
    int height() const { return image_.height; }
    bool on_border(int x, int y) const {
        return x == 0 || y == 0 || x == image_.width - 1 || y == image_.height - 1;
    }

private:
    const ImageView& image_;
};

// A pixel inside a flat area: more than two of its neighbours have exactly its colour (the
// image border counts as one, since a flat area may run off the edge).
bool inside_flat_area(const Pixels& img, int x, int y) {
    int equal = img.on_border(x, y) ? 1 : 0;
    const std::uint8_t* centre = img.at(x, y);
    for (int ny = std::max(y - 1, 0); ny <= std::min(y + 1, img.height() - 1); ++ny) {
        for (int nx = std::max(x - 1, 0); nx <= std::min(x + 1, img.width() - 1); ++nx) {
            if (nx == x && ny == y) continue;
            if (std::memcmp(centre, img.at(nx, ny), 4) == 0 && ++equal > 2) return true;
        }
    }
    return false;
}

// An anti-aliased edge pixel in `img` is a blend of two flat areas: among its neighbours it has
// both a brighter and a darker one, few of the same brightness, and the brightest or the
// darkest neighbour lies inside a flat area in both images (so the edge did not move; only its
// blend changed). pixelmatch's test, after Vysniauskas, "Anti-aliased pixel and intensity slope
// detector" (2009).
bool looks_anti_aliased(const Pixels& img, const Pixels& other, int x, int y) {
    int same_brightness = img.on_border(x, y) ? 1 : 0;
    const double centre = luma(on_white(img.at(x, y)));
    double brighter = 0, darker = 0;   // the largest brightness steps to a neighbour
    int bx = -1, by = -1, dx = -1, dy = -1;
    for (int ny = std::max(y - 1, 0); ny <= std::min(y + 1, img.height() - 1); ++ny) {
        for (int nx = std::max(x - 1, 0); nx <= std::min(x + 1, img.width() - 1); ++nx) {
            if (nx == x && ny == y) continue;
            const double step = luma(on_white(img.at(nx, ny))) - centre;
            if (step == 0) {
                if (++same_brightness > 2) return false;
            } else if (step > brighter) {
                brighter = step;
                bx = nx;
                by = ny;
            } else if (step < darker) {
                darker = step;
                dx = nx;
                dy = ny;
            }
        }
    }
    if (bx < 0 || dx < 0) return false;
    return (inside_flat_area(img, bx, by) && inside_flat_area(other, bx, by)) ||
           (inside_flat_area(img, dx, dy) && inside_flat_area(other, dx, dy));
}

void put(std::uint8_t* p, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    p[0] = r;
    p[1] = g;
    p[2] = b;
    p[3] = 255;
}

}  // namespace

double color_distance(const std::uint8_t* a, const std::uint8_t* b) {
    return std::min(1.0, std::sqrt(yiq_delta(a, b) / kMaxYiqDelta));
}

Comparison compare_images(const ImageView& actual, const ImageView& golden,
                          const CompareDef& def) {
    Comparison result;
    result.pixel_count = static_cast<std::int64_t>(actual.width) * actual.height;
    if (actual.width != golden.width || actual.height != golden.height) {
        result.same_size = false;
        return result;
    }
    if (std::equal(actual.rgba.begin(), actual.rgba.end(), golden.rgba.begin(),
                   golden.rgba.end())) {
        result.identical = true;
        return result;
    }

    const double limit = def.threshold * def.threshold * kMaxYiqDelta;
    const Pixels a(actual), g(golden);
    result.diff = {actual.width, actual.height, std::vector<std::uint8_t>(actual.rgba.size())};
    double worst = 0;
    for (int y = 0; y < actual.height; ++y) {
        for (int x = 0; x < actual.width; ++x) {
            std::uint8_t* out =
                result.diff.rgba.data() + 4 * (static_cast<std::size_t>(y) * actual.width + x);
            const double delta = yiq_delta(a.at(x, y), g.at(x, y));
            worst = std::max(worst, delta);
            if (delta <= limit) {
                const double grey = 255 + (luma(on_white(g.at(x, y))) - 255) * kDiffBackdropOpacity;
                const auto v = static_cast<std::uint8_t>(std::lround(std::clamp(grey, 0.0, 255.0)));
                put(out, v, v, v);
            } else if (def.detect_anti_aliasing &&
                       (looks_anti_aliased(a, g, x, y) || looks_anti_aliased(g, a, x, y))) {
                ++result.anti_aliased_pixels;
                put(out, 255, 210, 0);
            } else {
                ++result.differing_pixels;
                put(out, 255, 0, 0);
            }
        }
    }
    result.max_delta = std::min(1.0, std::sqrt(worst / kMaxYiqDelta));
    return result;
}

}  // namespace discreel::golden
