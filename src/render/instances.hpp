#pragma once
// Per-instance vertex data as the shaders read it, and the camera transform that produces it.
// Positions are pixels relative to the image centre, y up: the camera is applied here in
// double precision so far-from-origin scenes keep sub-pixel accuracy in float attributes.
#include <cstdint>
#include <span>
#include <vector>

#include "discreel/render.hpp"

namespace discreel::render {

struct DiscInstance {
    float center[2];   // pixels
    float radius;      // pixels
    float angle;       // radians
    float color[4];
    std::uint32_t flags;
};
// Match the constants of the same names in disc.vert (tests/render/shader_constants_test.cpp
// checks them against the embedded shader).
inline constexpr std::uint32_t kDiscStatic = 1;
inline constexpr std::uint32_t kDiscNoOutline = 2;
inline constexpr std::uint32_t kDiscNoSpinMarker = 4;

// Match the constants of the same names in disc.vert: a disc's quad or sprite is
// 2 (max(radius, kDiscMinRadius) + kDiscQuadMargin) pixels across.
inline constexpr float kDiscMinRadius = 0.5f;
inline constexpr float kDiscQuadMargin = 1.0f;

// Whether the disc can be drawn as a point sprite in a width x height frame: GL drops a point
// whose centre leaves the view (this keeps it a pixel inside) and caps the size of a sprite.
bool fits_point_sprite(const DiscInstance& disc, int width, int height, float max_point_size);

struct CapsuleInstance {
    float a[2];        // pixels
    float b[2];        // pixels
    float radius;      // pixels
    float color[4];
    std::uint32_t flags;
};
inline constexpr std::uint32_t kCapsuleFlat = 1;  // kFlat in capsule.frag (checked): no rim

struct PolygonInstance {
    float center[2];     // pixels
    float vertices[16];  // (x, y) pairs, pixels relative to the centre, rotated, y up
    float shape[4];      // vertex count, rounding (pixels), extent: farthest point (pixels),
                         // flags (kPolygon*, as a float)
    float spoke[3];      // unit vector along the body's x axis; the spin marker's length (px)
    float color[4];
};
// Flag bits of PolygonInstance::shape[3]; polygon.vert says the same (checked).
inline constexpr std::uint32_t kPolygonStatic = 1;
inline constexpr std::uint32_t kPolygonNoOutline = 2;
inline constexpr std::uint32_t kPolygonNoSpinMarker = 4;

// Replaces the contents of `out` (its capacity is reused from frame to frame).
void make_polygon_instances(const FrameScene& frame, double pixels_per_metre,
                            std::vector<PolygonInstance>& out);
// The same for a polygon, whose sprite is 2 (extent + kPolygonQuadMargin) pixels across.
inline constexpr float kPolygonQuadMargin = 1.0f;   // kQuadMargin in polygon.vert
bool fits_point_sprite(const PolygonInstance& polygon, int width, int height,
                       float max_point_size);
void make_disc_instances(const FrameScene& frame, double pixels_per_metre,
                         std::vector<DiscInstance>& out);
void make_capsule_instances(const FrameScene& frame, double pixels_per_metre,
                            std::vector<CapsuleInstance>& out);
// Flat lines (the frame's trails or joints), in the frame's camera.
void make_line_instances(const FrameScene& frame, std::span<const LineGeom> lines,
                         double pixels_per_metre, std::vector<CapsuleInstance>& out);
// Each arrow becomes three flat capsules: the shaft and two barbs.
void make_arrow_instances(const FrameScene& frame, double pixels_per_metre,
                          std::vector<CapsuleInstance>& out);

}  // namespace discreel::render
