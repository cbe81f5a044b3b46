#pragma once
// A vertex array fed by one per-instance buffer: each record becomes a quad (4-vertex triangle
// strip whose corners the vertex shader derives from gl_VertexID) or a point sprite, so a whole
// frame of discs is one upload and a few draw calls.
#include <cstddef>
#include <initializer_list>

#include "gl_objects.hpp"

namespace discreel::render {

struct InstanceAttribute {
    GLuint location;        // layout(location = ...) in the vertex shader
    GLint components;
    GLenum type;            // GL_FLOAT, or GL_UNSIGNED_INT for integer inputs
    std::size_t offset;     // bytes into the record
};

class InstanceStream {
public:
    static InstanceStream create(std::size_t record_size,
                                 std::initializer_list<InstanceAttribute> attributes);

    enum class Shape { quad, point };

    // Replaces the buffer's contents and draws one quad per record with the current program.
    void draw(const void* records, std::size_t count);
    // Replaces the buffer's contents, to be drawn by draw_uploaded.
    void upload(const void* records, std::size_t count);
    // Draws records [first, first + count) of the last upload with the current program.
    void draw_uploaded(Shape shape, std::size_t first, std::size_t count);

private:
    InstanceStream() = default;

    GlBuffer buffer_;
    GlVertexArray vertex_array_;
    std::size_t record_size_ = 0;
};

}  // namespace discreel::render
