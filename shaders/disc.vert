#version 330 core
// One point sprite or one quad per disc (instanced; a quad is a 4-vertex triangle strip built
// from gl_VertexID, no vertex buffer). Lengths are pixels, y up, origin at the image centre: the
// CPU already applied the camera in double precision.
//
// A point sprite is one primitive where a quad is two: llvmpipe sets up and bins half as many,
// and shades the 4x4 blocks along the quad's diagonal once instead of once per triangle. But GL
// drops a point whose centre is outside the view, however wide, and limits its size, so the
// renderer draws the discs that are cut by the frame's edge, or too big, as quads.
//
// Everything that depends on the disc alone (colours, widths, how much detail its size allows)
// is worked out here, four times per disc, rather than in the fragment shader for each of its
// few hundred pixels: on llvmpipe the fragment shader is most of a frame's drawing time.
layout(location = 0) in vec2 i_center;
layout(location = 1) in float i_radius;
layout(location = 2) in float i_angle;
layout(location = 3) in vec4 i_color;
layout(location = 4) in uint i_flags;

uniform vec2 u_pixels_to_ndc;   // (2/width, -2/height): the y flip puts the image top in GL row 0
uniform bool u_point_sprites;   // this draw's discs are points, not quads

out vec2 v_local;               // quads: this fragment relative to the disc centre, pixels, y up
flat out float v_half_size;     // points: half the sprite's side, pixels
flat out vec4 v_edges;          // pixels from the centre: edge, outline inside, ring inside;
                                // and the outline's strength (0 where the disc is too small)
flat out vec4 v_spoke;          // unit vector toward the spin angle; length, half width (px)
flat out vec4 v_fill;           // the disc's colour and alpha
flat out vec4 v_core;           // colour inside the ring; the spoke's strength
flat out vec3 v_outline_color;
flat out vec3 v_marker;

// The instance record's flag bits and the two sizes below are also in src/render/instances.hpp;
// ShaderConstantsTest checks that both say the same.
const uint kStatic = 1u;
const uint kNoOutline = 2u;
const uint kNoSpinMarker = 4u;

// Half a pixel of anti-aliasing ramp lies outside the edge; one pixel of slack keeps the quad
// from clipping it.
const float kQuadMargin = 1.0;
// Smaller discs would fall between pixel centres and vanish: keep them one pixel across.
const float kMinRadius = 0.5;
// A ring this far inside puts every pixel of the disc outside it: moving discs have none.
const float kNoRing = -1e6;

float luminance(vec3 c) {
    return dot(c, vec3(0.299, 0.587, 0.114));
}

void main() {
    float r = max(i_radius, kMinRadius);
    v_half_size = r + kQuadMargin;
    if (u_point_sprites) {
        v_local = vec2(0.0);
        gl_PointSize = 2.0 * v_half_size;
        gl_Position = vec4(i_center * u_pixels_to_ndc, 0.0, 1.0);
    } else {
        vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
        v_local = corner * v_half_size;
        gl_Position = vec4((i_center + v_local) * u_pixels_to_ndc, 0.0, 1.0);
    }

    vec3 fill = i_color.rgb;
    // Outlines and markers need room: fade them in as the disc grows past a few pixels, so a
    // tiny disc stays its own colour rather than a smudge of outline.
    float outline = (i_flags & kNoOutline) != 0u ? 0.0 : smoothstep(2.0, 5.0, r);
    float outline_width = clamp(0.08 * r, 1.0, 3.0);
    v_fill = i_color;
    if ((i_flags & kStatic) != 0u) {
        // A peg: a darker core inside a ring, a darker outline, no spoke.
        v_edges = vec4(r, r - outline_width, r * 0.62, outline);
        v_core = vec4(fill * 0.55, 0.0);
        v_outline_color = fill * 0.45;
        v_marker = fill;
        v_spoke = vec4(1.0, 0.0, 0.0, 0.0);
    } else {
        // A moving disc: a contrasting spoke toward its angle, so spin shows.
        v_edges = vec4(r, r - outline_width, kNoRing, outline);
        float spoke = (i_flags & kNoSpinMarker) != 0u ? 0.0 : smoothstep(3.0, 6.0, r);
        v_core = vec4(fill, spoke);
        v_outline_color = fill * 0.62;
        v_marker = luminance(fill) > 0.5 ? fill * 0.25 : mix(fill, vec3(1.0), 0.8);
        v_spoke = vec4(cos(i_angle), sin(i_angle), r - outline_width - 0.1 * r,
                       max(0.07 * r, 0.6));
    }
}
