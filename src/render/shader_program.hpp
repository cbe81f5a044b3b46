#pragma once
// Compiles and links a vertex + fragment shader pair in the current context. Failures carry
// the GL info log, so a broken shader names its line.
#include <string_view>

#include "discreel/expected.hpp"
#include "gl_objects.hpp"

namespace discreel::render {

Expected<GlProgram> build_program(std::string_view vertex_source,
                                  std::string_view fragment_source);

}  // namespace discreel::render
