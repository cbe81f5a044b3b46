#pragma once
// The RGBA8 framebuffer object every frame is drawn into and read back from.
//
// Why an FBO and not OSMesa's own colour buffer: its format is exactly what we ask for (RGBA8,
// no depth, no sRGB), its completeness is checked, and the bytes do not depend on how OSMesa
// copies its back buffer out. The two paths differ by one unit on some pixels, so the goldens
// are tied to this one.
#include <cstdint>
#include <span>

#include "discreel/expected.hpp"
#include "gl_objects.hpp"

namespace discreel::render {

class OffscreenTarget {
public:
    // Binds the target for drawing and sets the viewport to cover it.
    static Expected<OffscreenTarget> create(int width, int height);

    // Reads the whole target as RGBA8 rows from GL row 0 upward into `out`
    // (4 * width * height bytes).
    void read(std::span<std::uint8_t> out) const;

private:
    OffscreenTarget() = default;

    GlRenderbuffer color_;
    GlFramebuffer framebuffer_;
    int width_ = 0;
    int height_ = 0;
};

}  // namespace discreel::render
