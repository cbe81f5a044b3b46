#include "shader_program.hpp"

#include <string>

namespace discreel::render {
namespace {

std::string shader_log(GLuint shader) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 0 ? length : 0), '\0');
    GLsizei written = 0;
    glGetShaderInfoLog(shader, length, &written, log.data());
    log.resize(static_cast<std::size_t>(written));
    return log;
}

std::string program_log(GLuint program) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 0 ? length : 0), '\0');
    GLsizei written = 0;
    glGetProgramInfoLog(program, length, &written, log.data());
    log.resize(static_cast<std::size_t>(written));
    return log;
}

Expected<GlShader> compile(GLenum stage, std::string_view source, const char* stage_name) {
    GlShader shader(glCreateShader(stage));
    if (shader.id() == 0) {
        return Error{std::string("cannot create a ") + stage_name + " shader"};
    }
    const GLchar* text = source.data();
    const auto length = static_cast<GLint>(source.size());
    glShaderSource(shader.id(), 1, &text, &length);
    glCompileShader(shader.id());
    GLint compiled = GL_FALSE;
    glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &compiled);
    if (compiled != GL_TRUE) {
        return Error{std::string(stage_name) + " shader failed to compile: " +
                     shader_log(shader.id())};
    }
    return shader;
}

}  // namespace

Expected<GlProgram> build_program(std::string_view vertex_source,
                                  std::string_view fragment_source) {
    auto vertex = compile(GL_VERTEX_SHADER, vertex_source, "vertex");
    if (!vertex) return vertex.error();
    auto fragment = compile(GL_FRAGMENT_SHADER, fragment_source, "fragment");
    if (!fragment) return fragment.error();

    GlProgram program = GlProgram::generate();
    if (program.id() == 0) return Error{"cannot create a shader program"};
    glAttachShader(program.id(), vertex->id());
    glAttachShader(program.id(), fragment->id());
    glLinkProgram(program.id());
    // The program keeps the compiled code; the shader objects can go with this scope.
    glDetachShader(program.id(), vertex->id());
    glDetachShader(program.id(), fragment->id());
    GLint linked = GL_FALSE;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &linked);
    if (linked != GL_TRUE) {
        return Error{"shader program failed to link: " + program_log(program.id())};
    }
    return program;
}

}  // namespace discreel::render
