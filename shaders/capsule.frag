#version 330 core
// Signed-distance capsule: a wall (fill with a subtle darker outline) or a flat line (trails,
// arrows), edges anti-aliased over one pixel like the discs.
in vec2 v_local;
flat in vec2 v_ab;
flat in float v_radius;
flat in vec4 v_color;
flat in uint v_flags;

out vec4 o_color;

const uint kFlat = 1u;  // kCapsuleFlat in src/render/instances.hpp (ShaderConstantsTest)

float coverage(float signed_distance) {
    return clamp(0.5 - signed_distance, 0.0, 1.0);
}

void main() {
    float len2 = dot(v_ab, v_ab);
    float t = len2 > 0.0 ? clamp(dot(v_local, v_ab) / len2, 0.0, 1.0) : 0.0;
    float dist = length(v_local - v_ab * t);
    float edge = coverage(dist - v_radius);
    if (edge <= 0.0) discard;

    float outline_width = clamp(0.15 * v_radius, 1.0, 2.0);
    float in_outline = 1.0 - coverage(dist - (v_radius - outline_width));
    float detail = (v_flags & kFlat) != 0u ? 0.0 : smoothstep(2.0, 4.0, v_radius);
    vec3 color = mix(v_color.rgb, v_color.rgb * 0.62, in_outline * detail);
    o_color = vec4(color, v_color.a * edge);
}
