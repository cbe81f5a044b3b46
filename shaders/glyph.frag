#version 330 core
// A dot of the glyph is either fully drawn or not at all: the font is a pixel font, scaled by
// whole pixels, so it needs no anti-aliasing.
in vec2 v_dots;
flat in uvec2 v_bits;   // rows 0-3, rows 4-6; 5 bits a row, left column lowest
flat in vec4 v_color;

out vec4 o_color;

void main() {
    ivec2 cell = clamp(ivec2(floor(v_dots)), ivec2(0), ivec2(4, 6));
    uint row_bits = cell.y < 4 ? v_bits.x >> uint(cell.y * 5) : v_bits.y >> uint((cell.y - 4) * 5);
    if (((row_bits >> uint(cell.x)) & 1u) == 0u) discard;
    o_color = v_color;
}
