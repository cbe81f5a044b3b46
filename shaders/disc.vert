#version 330 core
// One quad per disc (instanced, 4-vertex triangle strip built from gl_VertexID, no vertex
// buffer). Lengths are pixels, y up, origin at the image centre: the CPU already applied the
// camera in double precision.
layout(location = 0) in vec2 i_center;
layout(location = 1) in float i_radius;
layout(location = 2) in float i_angle;
layout(location = 3) in vec4 i_color;
layout(location = 4) in uint i_flags;

uniform vec2 u_pixels_to_ndc;   // (2/width, -2/height): the y flip puts the image top in GL row 0

out vec2 v_local;               // this fragment relative to the disc centre, pixels, y up
flat out float v_radius;        // pixels
flat out vec2 v_spoke;          // unit vector toward the spin angle
flat out vec4 v_color;
flat out uint v_flags;

// Half a pixel of anti-aliasing ramp lies outside the edge; one pixel of slack keeps the quad
// from clipping it.
const float kQuadMargin = 1.0;
// Smaller discs would fall between pixel centres and vanish: keep them one pixel across.
const float kMinRadius = 0.5;

void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
    v_radius = max(i_radius, kMinRadius);
    v_local = corner * (v_radius + kQuadMargin);
    v_spoke = vec2(cos(i_angle), sin(i_angle));
    v_color = i_color;
    v_flags = i_flags;
    gl_Position = vec4((i_center + v_local) * u_pixels_to_ndc, 0.0, 1.0);
}
