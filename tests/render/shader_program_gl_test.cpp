// Shader build failures come back as errors carrying the GL info log. The embedded shaders
// compile, so this reaches the module's internal build_program with broken sources.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <optional>
#include <utility>

#include "osmesa_context.hpp"
#include "shader_program.hpp"

namespace discreel::render {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr const char* kVertex = R"(#version 330 core
out vec2 v_uv;
void main() { v_uv = vec2(0.0); gl_Position = vec4(0.0, 0.0, 0.0, 1.0); }
)";

constexpr const char* kFragment = R"(#version 330 core
in vec2 v_uv;
out vec4 o_color;
void main() { o_color = vec4(v_uv, 0.0, 1.0); }
)";

class ShaderProgramGLTest : public ::testing::Test {
protected:
    void SetUp() override {
        auto created = OsmesaContext::create();
        ASSERT_TRUE(created.ok()) << created.error().message;
        context_.emplace(std::move(created.value()));
    }
    std::optional<OsmesaContext> context_;
};

TEST_F(ShaderProgramGLTest, ValidSourcesLink) {
    auto program = build_program(kVertex, kFragment);
    ASSERT_TRUE(program.ok()) << program.error().message;
    EXPECT_NE(program->id(), 0u);
}

TEST_F(ShaderProgramGLTest, CompileErrorCarriesTheInfoLog) {
    auto program = build_program(kVertex, R"(#version 330 core
out vec4 o_color;
void main() { o_color = vec4(undeclared_brightness); }
)");
    ASSERT_FALSE(program.ok());
    EXPECT_THAT(program.error().message, StartsWith("fragment shader failed to compile: "));
    // Mesa's log names the line and the offending identifier.
    EXPECT_THAT(program.error().message, HasSubstr("0:3("));
    EXPECT_THAT(program.error().message, HasSubstr("undeclared_brightness"));
}

TEST_F(ShaderProgramGLTest, VertexCompileErrorNamesTheVertexStage) {
    auto program = build_program("#version 330 core\nvoid main() { gl_Position = 1; }\n", kFragment);
    ASSERT_FALSE(program.ok());
    EXPECT_THAT(program.error().message, StartsWith("vertex shader failed to compile: "));
}

TEST_F(ShaderProgramGLTest, LinkErrorCarriesTheInfoLog) {
    // Each stage compiles on its own; only linking sees that v_uv's types disagree.
    auto program = build_program(kVertex, R"(#version 330 core
in vec3 v_uv;
out vec4 o_color;
void main() { o_color = vec4(v_uv, 1.0); }
)");
    ASSERT_FALSE(program.ok());
    EXPECT_THAT(program.error().message, StartsWith("shader program failed to link: "));
    EXPECT_THAT(program.error().message, HasSubstr("v_uv"));
}

}  // namespace
}  // namespace discreel::render
