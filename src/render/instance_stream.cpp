#include "instance_stream.hpp"

namespace discreel::render {

InstanceStream InstanceStream::create(std::size_t record_size,
                                      std::initializer_list<InstanceAttribute> attributes) {
    InstanceStream stream;
    stream.record_size_ = record_size;
    stream.buffer_ = GlBuffer::generate();
    stream.vertex_array_ = GlVertexArray::generate();
    glBindVertexArray(stream.vertex_array_.id());
    glBindBuffer(GL_ARRAY_BUFFER, stream.buffer_.id());
    const auto stride = static_cast<GLsizei>(record_size);
    for (const InstanceAttribute& a : attributes) {
        glEnableVertexAttribArray(a.location);
        // GL takes the attribute's byte offset in the buffer as a pointer.
        // NOLINTNEXTLINE(performance-no-int-to-ptr)
        const auto* offset = reinterpret_cast<const void*>(a.offset);
        if (a.type == GL_UNSIGNED_INT) {
            glVertexAttribIPointer(a.location, a.components, a.type, stride, offset);
        } else {
            glVertexAttribPointer(a.location, a.components, a.type, GL_FALSE, stride, offset);
        }
        glVertexAttribDivisor(a.location, 1);
    }
    glBindVertexArray(0);
    return stream;
}

void InstanceStream::draw(const void* records, std::size_t count) {
    upload(records, count);
    draw_uploaded(Shape::quad, 0, count);
}

void InstanceStream::upload(const void* records, std::size_t count) {
    if (count == 0) return;
    // glBufferData with fresh contents orphans the previous frame's storage rather than
    // waiting for a draw that may still read it.
    glBindBuffer(GL_ARRAY_BUFFER, buffer_.id());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(count * record_size_), records,
                 GL_STREAM_DRAW);
}

void InstanceStream::draw_uploaded(Shape shape, std::size_t first, std::size_t count) {
    if (count == 0) return;
    glBindVertexArray(vertex_array_.id());
    const bool quad = shape == Shape::quad;
    glDrawArraysInstancedBaseInstance(quad ? GL_TRIANGLE_STRIP : GL_POINTS, 0, quad ? 4 : 1,
                                      static_cast<GLsizei>(count), static_cast<GLuint>(first));
}

}  // namespace discreel::render
