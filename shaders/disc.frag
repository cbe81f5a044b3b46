#version 330 core
// Signed-distance disc: fill, a subtle darker outline and, on moving discs, a contrasting
// spoke toward the spin angle. Static discs (pegs) get a darker core inside a ring instead.
// Flags switch the outline and the spoke off.
// Every edge is anti-aliased over one pixel: coverage = clamp(0.5 - distance, 0, 1).
in vec2 v_local;
flat in float v_radius;
flat in vec2 v_spoke;
flat in vec4 v_color;
flat in uint v_flags;

out vec4 o_color;

const uint kStatic = 1u;
const uint kNoOutline = 2u;
const uint kNoSpinMarker = 4u;

float coverage(float signed_distance) {
    return clamp(0.5 - signed_distance, 0.0, 1.0);
}

float luminance(vec3 c) {
    return dot(c, vec3(0.299, 0.587, 0.114));
}

void main() {
    float r = v_radius;
    float dist = length(v_local);
    float edge = coverage(dist - r);
    if (edge <= 0.0) discard;

    vec3 fill = v_color.rgb;
    // Outlines and markers need room: fade them in as the disc grows past a few pixels, so a
    // tiny disc stays its own colour rather than a smudge of outline.
    float detail = smoothstep(2.0, 5.0, r);
    float outline = (v_flags & kNoOutline) != 0u ? 0.0 : detail;

    float outline_width = clamp(0.08 * r, 1.0, 3.0);
    float in_outline = 1.0 - coverage(dist - (r - outline_width));
    vec3 color;
    if ((v_flags & kStatic) != 0u) {
        vec3 core = fill * 0.55;
        float ring_inner = r * 0.62;
        color = mix(core, fill, 1.0 - coverage(dist - ring_inner));
        color = mix(color, fill * 0.45, in_outline * outline);
    } else {
        color = mix(fill, fill * 0.62, in_outline * outline);
        vec3 marker = luminance(fill) > 0.5 ? fill * 0.25 : mix(fill, vec3(1.0), 0.8);
        float spoke_length = r - outline_width - 0.1 * r;
        float spoke_half_width = max(0.07 * r, 0.6);
        float along = clamp(dot(v_local, v_spoke), 0.0, spoke_length);
        float spoke_dist = length(v_local - v_spoke * along) - spoke_half_width;
        float spoke = (v_flags & kNoSpinMarker) != 0u ? 0.0 : smoothstep(3.0, 6.0, r);
        color = mix(color, marker, coverage(spoke_dist) * spoke);
    }
    o_color = vec4(color, v_color.a * edge);
}
