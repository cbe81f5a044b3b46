#version 330 core
// One point sprite or one quad per convex polygon (instanced; a quad is a 4-vertex triangle
// strip from gl_VertexID), a square around its bounding circle padded by a pixel for the
// anti-aliasing ramp: points where they fit, for the reason disc.vert gives. The outline arrives
// already rotated and scaled to pixels, relative to the centre. Pixels, y up, origin at the
// image centre.
layout(location = 0) in vec2 i_center;
layout(location = 1) in vec4 i_v01;      // vertices 0 and 1
layout(location = 2) in vec4 i_v23;
layout(location = 3) in vec4 i_v45;
layout(location = 4) in vec4 i_v67;
layout(location = 5) in vec4 i_shape;    // vertex count, rounding (pixels), extent (pixels), flags
layout(location = 6) in vec3 i_spoke;    // unit vector along the body's x axis; length (pixels)
layout(location = 7) in vec4 i_color;

uniform vec2 u_pixels_to_ndc;   // (2/width, -2/height): the y flip puts the image top in GL row 0
uniform bool u_point_sprites;   // this draw's polygons are points, not quads

out vec2 v_local;               // quads: this fragment relative to the centre, pixels
flat out float v_half_size;     // points: half the sprite's side, pixels
flat out vec4 v_v01;
flat out vec4 v_v23;
flat out vec4 v_v45;
flat out vec4 v_v67;
flat out vec2 v_shape;          // vertex count, rounding
flat out vec4 v_color;          // fill (darker for a static body) and alpha
flat out vec4 v_outline;        // rim colour; its strength (0: no rim)
flat out vec4 v_spoke;          // unit direction, length, half width (pixels)
flat out vec4 v_marker;         // spoke colour; its strength (0: no spoke)

// The flag bits and the margin are also in src/render/instances.hpp; ShaderConstantsTest
// checks that both say the same.
const uint kStatic = 1u;
const uint kNoOutline = 2u;
const uint kNoSpinMarker = 4u;
const float kQuadMargin = 1.0;

float luminance(vec3 c) {
    return dot(c, vec3(0.299, 0.587, 0.114));
}

void main() {
    float pad = i_shape.z + kQuadMargin;
    v_half_size = pad;
    v_v01 = i_v01;
    v_v23 = i_v23;
    v_v45 = i_v45;
    v_v67 = i_v67;
    v_shape = i_shape.xy;
    uint flags = uint(i_shape.w + 0.5);
    bool fixed_body = (flags & kStatic) != 0u;
    // As on discs: rims and markers fade in as the body grows past a few pixels, and a static
    // body is darker and has no marker.
    vec3 fill = fixed_body ? i_color.rgb * 0.55 : i_color.rgb;
    v_color = vec4(fill, i_color.a);
    float size = i_shape.z;
    v_outline = vec4(fill * 0.62, (flags & kNoOutline) != 0u ? 0.0 : smoothstep(2.0, 5.0, size));
    float spoke = fixed_body || (flags & kNoSpinMarker) != 0u ? 0.0 : smoothstep(3.0, 6.0, i_spoke.z);
    v_marker = vec4(luminance(fill) > 0.5 ? fill * 0.25 : mix(fill, vec3(1.0), 0.8), spoke);
    v_spoke = vec4(i_spoke.xy, i_spoke.z, max(0.07 * i_spoke.z, 0.6));
    if (u_point_sprites) {
        v_local = vec2(0.0);
        gl_PointSize = 2.0 * pad;
        gl_Position = vec4(i_center * u_pixels_to_ndc, 0.0, 1.0);
    } else {
        vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
        v_local = corner * pad;
        gl_Position = vec4((i_center + v_local) * u_pixels_to_ndc, 0.0, 1.0);
    }
}
