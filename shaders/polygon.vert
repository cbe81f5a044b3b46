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
layout(location = 5) in vec3 i_shape;    // vertex count, rounding (pixels), extent (pixels)
layout(location = 6) in vec4 i_color;

uniform vec2 u_pixels_to_ndc;   // (2/width, -2/height): the y flip puts the image top in GL row 0
uniform bool u_point_sprites;   // this draw's polygons are points, not quads

out vec2 v_local;               // quads: this fragment relative to the centre, pixels
flat out float v_half_size;     // points: half the sprite's side, pixels
flat out vec4 v_v01;
flat out vec4 v_v23;
flat out vec4 v_v45;
flat out vec4 v_v67;
flat out vec2 v_shape;          // vertex count, rounding
flat out vec4 v_color;

const float kQuadMargin = 1.0;

void main() {
    float pad = i_shape.z + kQuadMargin;
    v_half_size = pad;
    v_v01 = i_v01;
    v_v23 = i_v23;
    v_v45 = i_v45;
    v_v67 = i_v67;
    v_shape = i_shape.xy;
    v_color = i_color;
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
