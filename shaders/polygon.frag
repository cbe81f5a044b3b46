#version 330 core
// Signed distance to a convex polygon swept by a rounding radius: inside, the largest signed
// distance to an edge's line; outside, the distance to the nearest edge. Edges anti-aliased
// over one pixel, a darker rim and a spin marker along the body's x axis, as on discs.
in vec2 v_local;
flat in float v_half_size;
flat in vec4 v_v01;
flat in vec4 v_v23;
flat in vec4 v_v45;
flat in vec4 v_v67;
flat in vec2 v_shape;
flat in vec4 v_color;
flat in vec4 v_outline;
flat in vec4 v_spoke;
flat in vec4 v_marker;

uniform bool u_point_sprites;

out vec4 o_color;

float coverage(float signed_distance) {
    return clamp(0.5 - signed_distance, 0.0, 1.0);
}

vec2 vertex(int i) {
    if (i == 0) return v_v01.xy;
    if (i == 1) return v_v01.zw;
    if (i == 2) return v_v23.xy;
    if (i == 3) return v_v23.zw;
    if (i == 4) return v_v45.xy;
    if (i == 5) return v_v45.zw;
    if (i == 6) return v_v67.xy;
    return v_v67.zw;
}

void main() {
    // As in disc.frag: gl_PointCoord's (0, 0) to (1, 1) maps onto -half to +half, y up.
    vec2 local = u_point_sprites ? (gl_PointCoord * 2.0 - 1.0) * v_half_size : v_local;
    int count = int(v_shape.x + 0.5);
    float rounding = v_shape.y;
    // Inside the core the largest signed distance to an edge line is the distance to the
    // outline; outside it is a lower bound of it, so far pixels are dropped before the exact
    // distance to the nearest edge is taken (on llvmpipe the fragment shader is the cost).
    float inside = -1e30;
    if (count > 2) {
        for (int i = 0; i < count; ++i) {
            vec2 a = vertex(i);
            vec2 edge = vertex(i + 1 == count ? 0 : i + 1) - a;
            float scale = inversesqrt(max(dot(edge, edge), 1e-12));
            inside = max(inside, dot(local - a, vec2(edge.y, -edge.x)) * scale);
        }
        if (inside - rounding >= 0.5) discard;
    }
    float dist = inside;
    if (count <= 2 || inside > 0.0) {
        dist = 1e30;
        for (int i = 0; i < count; ++i) {
            vec2 a = vertex(i);
            vec2 edge = vertex(i + 1 == count ? 0 : i + 1) - a;
            float len2 = dot(edge, edge);
            float t = len2 > 0.0 ? clamp(dot(local - a, edge) / len2, 0.0, 1.0) : 0.0;
            dist = min(dist, length(local - a - edge * t));
        }
    }
    float edge = coverage(dist - rounding);
    if (edge <= 0.0) discard;

    float outline_width = 1.5;
    float in_outline = 1.0 - coverage(dist - rounding + outline_width);
    vec3 color = mix(v_color.rgb, v_outline.rgb, in_outline * v_outline.a);
    float along = clamp(dot(local, v_spoke.xy), 0.0, v_spoke.z);
    float spoke_dist = length(local - v_spoke.xy * along) - v_spoke.w;
    color = mix(color, v_marker.rgb, coverage(spoke_dist) * v_marker.a);
    o_color = vec4(color, v_color.a * edge);
}
