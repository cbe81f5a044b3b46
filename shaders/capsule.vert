#version 330 core
// One quad per capsule (instanced, 4-vertex triangle strip from gl_VertexID), aligned with the
// segment and padded by the radius plus a pixel for the anti-aliasing ramp. Pixels, y up,
// origin at the image centre.
layout(location = 0) in vec2 i_a;
layout(location = 1) in vec2 i_b;
layout(location = 2) in float i_radius;
layout(location = 3) in vec4 i_color;
layout(location = 4) in uint i_flags;

uniform vec2 u_pixels_to_ndc;   // (2/width, -2/height): the y flip puts the image top in GL row 0

out vec2 v_local;               // this fragment relative to end a, pixels, y up
flat out vec2 v_ab;             // b - a, pixels
flat out float v_radius;        // pixels
flat out vec4 v_color;
flat out uint v_flags;

const float kQuadMargin = 1.0;
const float kMinRadius = 0.5;   // hairline walls stay one pixel wide

void main() {
    v_radius = max(i_radius, kMinRadius);
    v_ab = i_b - i_a;
    float len = length(v_ab);
    vec2 along = len > 0.0 ? v_ab / len : vec2(1.0, 0.0);
    vec2 across = vec2(-along.y, along.x);
    float pad = v_radius + kQuadMargin;
    float t = float(gl_VertexID & 1);
    float side = float(gl_VertexID >> 1) * 2.0 - 1.0;
    v_local = along * (t * len + (t * 2.0 - 1.0) * pad) + across * (side * pad);
    v_color = i_color;
    v_flags = i_flags;
    gl_Position = vec4((i_a + v_local) * u_pixels_to_ndc, 0.0, 1.0);
}
