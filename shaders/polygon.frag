#version 330 core
// Signed distance to a convex polygon swept by a rounding radius: inside, the largest signed
// distance to an edge's line; outside, the distance to the nearest edge. Edges anti-aliased
// over one pixel and a darker rim, as on discs.
in vec2 v_local;
flat in vec4 v_v01;
flat in vec4 v_v23;
flat in vec4 v_v45;
flat in vec4 v_v67;
flat in vec2 v_shape;
flat in vec4 v_color;

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
    int count = int(v_shape.x + 0.5);
    float inside = -1e30;    // largest signed distance to an edge line (counter-clockwise)
    float nearest = 1e30;    // distance to the nearest edge segment
    for (int i = 0; i < count; ++i) {
        vec2 a = vertex(i);
        vec2 b = vertex(i + 1 == count ? 0 : i + 1);
        vec2 edge = b - a;
        float len2 = dot(edge, edge);
        float t = len2 > 0.0 ? clamp(dot(v_local - a, edge) / len2, 0.0, 1.0) : 0.0;
        nearest = min(nearest, length(v_local - a - edge * t));
        if (len2 > 0.0) inside = max(inside, dot(v_local - a, vec2(edge.y, -edge.x)) / sqrt(len2));
    }
    // A capsule's two "edges" are one segment both ways: never inside, only near.
    float dist = (count > 2 && inside <= 0.0) ? inside : nearest;
    float rounding = v_shape.y;
    float edge = coverage(dist - rounding);
    if (edge <= 0.0) discard;

    float outline_width = 1.5;
    float in_outline = 1.0 - coverage(dist - rounding + outline_width);
    vec3 color = mix(v_color.rgb, v_color.rgb * 0.62, in_outline);
    o_color = vec4(color, v_color.a * edge);
}
