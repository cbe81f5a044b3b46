#version 330 core
// One quad per glyph (instanced, 4-vertex triangle strip from gl_VertexID) covering its 5x7
// dots. Origins are whole pixels, so dot edges fall on pixel edges and text stays crisp.
layout(location = 0) in vec2 i_origin;   // top-left corner, pixels from the image centre, y up
layout(location = 1) in float i_dot;     // pixels per dot
layout(location = 2) in uvec2 i_bits;    // rows 0-3, rows 4-6; 5 bits a row, left column lowest
layout(location = 3) in vec4 i_color;

uniform vec2 u_pixels_to_ndc;   // (2/width, -2/height): the y flip puts the image top in GL row 0

out vec2 v_dots;                // position in dots from the top-left corner, y down
flat out uvec2 v_bits;
flat out vec4 v_color;

void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    v_dots = corner * vec2(5.0, 7.0);
    v_bits = i_bits;
    v_color = i_color;
    vec2 offset = vec2(v_dots.x, -v_dots.y) * i_dot;
    gl_Position = vec4((i_origin + offset) * u_pixels_to_ndc, 0.0, 1.0);
}
