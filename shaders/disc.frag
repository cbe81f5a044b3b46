#version 330 core
// Signed-distance disc: fill, a subtle darker outline and, on moving discs, a contrasting
// spoke toward the spin angle. Static discs (pegs) get a darker core inside a ring instead.
// The vertex shader chose the colours and widths per disc (a peg's spoke and a moving disc's
// ring have zero strength), so every disc runs the same few steps here with no branches.
// Every edge is anti-aliased over one pixel: coverage = clamp(0.5 - distance, 0, 1).
uniform bool u_point_sprites;

in vec2 v_local;
flat in float v_half_size;
flat in vec4 v_edges;
flat in vec4 v_spoke;
flat in vec4 v_fill;
flat in vec4 v_core;
flat in vec3 v_outline_color;
flat in vec3 v_marker;

out vec4 o_color;

float coverage(float signed_distance) {
    return clamp(0.5 - signed_distance, 0.0, 1.0);
}

void main() {
    // gl_PointCoord runs from the sprite's top left, and the frame's rows are flipped (image top
    // in GL row 0), so (0, 0) to (1, 1) maps onto -half to +half on both axes, y up.
    vec2 local = u_point_sprites ? (gl_PointCoord * 2.0 - 1.0) * v_half_size : v_local;
    float dist = length(local);
    float edge = coverage(dist - v_edges.x);
    if (edge <= 0.0) discard;

    // mix(c, c, t) is exactly c, so a moving disc (core = fill) is its fill colour here.
    vec3 color = mix(v_core.rgb, v_fill.rgb, 1.0 - coverage(dist - v_edges.z));
    float in_outline = 1.0 - coverage(dist - v_edges.y);
    color = mix(color, v_outline_color, in_outline * v_edges.w);
    float along = clamp(dot(local, v_spoke.xy), 0.0, v_spoke.z);
    float spoke_dist = length(local - v_spoke.xy * along) - v_spoke.w;
    color = mix(color, v_marker, coverage(spoke_dist) * v_core.a);
    o_color = vec4(color, v_fill.a * edge);
}
