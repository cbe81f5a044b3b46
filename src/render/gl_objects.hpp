#pragma once
// Move-only owners of GL object names. Each must be destroyed while the context that created
// it is current (the Renderer makes its context current before tearing down).
#include <utility>

#include "gl.hpp"

namespace discreel::render {

template <class Kind>
class GlObject {
public:
    GlObject() = default;
    explicit GlObject(GLuint id) : id_(id) {}
    ~GlObject() { reset(); }
    GlObject(GlObject&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
    GlObject& operator=(GlObject&& other) noexcept {
        if (this != &other) {
            reset();
            id_ = std::exchange(other.id_, 0);
        }
        return *this;
    }
    GlObject(const GlObject&) = delete;
    GlObject& operator=(const GlObject&) = delete;

    // For kinds whose names come from glGen* (buffers, vertex arrays, ...).
    static GlObject generate() { return GlObject(Kind::generate()); }

    GLuint id() const { return id_; }

private:
    void reset() {
        if (id_ != 0) Kind::destroy(id_);
        id_ = 0;
    }
    GLuint id_ = 0;
};

struct BufferKind {
    static GLuint generate() { GLuint id = 0; glGenBuffers(1, &id); return id; }
    static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct VertexArrayKind {
    static GLuint generate() { GLuint id = 0; glGenVertexArrays(1, &id); return id; }
    static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct FramebufferKind {
    static GLuint generate() { GLuint id = 0; glGenFramebuffers(1, &id); return id; }
    static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct RenderbufferKind {
    static GLuint generate() { GLuint id = 0; glGenRenderbuffers(1, &id); return id; }
    static void destroy(GLuint id) { glDeleteRenderbuffers(1, &id); }
};
struct ShaderKind {
    static void destroy(GLuint id) { glDeleteShader(id); }
};
struct ProgramKind {
    static GLuint generate() { return glCreateProgram(); }
    static void destroy(GLuint id) { glDeleteProgram(id); }
};

using GlBuffer = GlObject<BufferKind>;
using GlVertexArray = GlObject<VertexArrayKind>;
using GlFramebuffer = GlObject<FramebufferKind>;
using GlRenderbuffer = GlObject<RenderbufferKind>;
using GlShader = GlObject<ShaderKind>;
using GlProgram = GlObject<ProgramKind>;

}  // namespace discreel::render
