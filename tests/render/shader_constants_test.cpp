// The instance records' flag bits and the disc quad's size rules live twice: in instances.hpp,
// where the CPU fills the records and sizes point sprites, and in the shaders that read them.
// This reads the embedded shader sources (no GL needed) and checks that each constant the
// shaders declare has the value the C++ side uses, so that neither can change alone.
#include <gtest/gtest.h>

#include <charconv>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "discreel_shaders.hpp"
#include "instances.hpp"

namespace discreel::render {
namespace {

// The value of `const <type> <name> = <value>;` in a shader source, as written (without a
// trailing 'u'), or nothing if the source declares no such constant.
std::optional<std::string> shader_constant(std::string_view source, std::string_view type,
                                           std::string_view name) {
    const std::string declaration = "const " + std::string(type) + " " + std::string(name) + " = ";
    const std::size_t at = source.find(declaration);
    if (at == std::string_view::npos) return std::nullopt;
    const std::size_t begin = at + declaration.size();
    const std::size_t end = source.find(';', begin);
    if (end == std::string_view::npos) return std::nullopt;
    std::string value(source.substr(begin, end - begin));
    if (!value.empty() && value.back() == 'u') value.pop_back();
    return value;
}

// The constant parsed as a T, or nothing if it is missing or not wholly a T.
template <typename T>
std::optional<T> parsed_constant(std::string_view source, std::string_view type,
                                 std::string_view name) {
    const std::optional<std::string> text = shader_constant(source, type, name);
    if (!text) return std::nullopt;
    T value{};
    const auto [end, error] = std::from_chars(text->data(), text->data() + text->size(), value);
    if (error != std::errc{} || end != text->data() + text->size()) return std::nullopt;
    return value;
}

std::optional<std::uint32_t> shader_uint(std::string_view source, std::string_view name) {
    return parsed_constant<std::uint32_t>(source, "uint", name);
}

std::optional<float> shader_float(std::string_view source, std::string_view name) {
    return parsed_constant<float>(source, "float", name);
}

TEST(ShaderConstantsTest, DiscFlagsMatchTheInstanceRecord) {
    EXPECT_EQ(shader_uint(discreel_shaders::disc_vert, "kStatic"), kDiscStatic);
    EXPECT_EQ(shader_uint(discreel_shaders::disc_vert, "kNoOutline"), kDiscNoOutline);
    EXPECT_EQ(shader_uint(discreel_shaders::disc_vert, "kNoSpinMarker"), kDiscNoSpinMarker);
}

TEST(ShaderConstantsTest, DiscQuadSizeMatchesThePointSpriteTest) {
    // fits_point_sprite sizes a disc's sprite with these; the shader sizes the quad or sprite.
    EXPECT_EQ(shader_float(discreel_shaders::disc_vert, "kMinRadius"), kDiscMinRadius);
    EXPECT_EQ(shader_float(discreel_shaders::disc_vert, "kQuadMargin"), kDiscQuadMargin);
}

TEST(ShaderConstantsTest, PolygonFlagsMatchTheInstanceRecord) {
    EXPECT_EQ(shader_uint(discreel_shaders::polygon_vert, "kStatic"), kPolygonStatic);
    EXPECT_EQ(shader_uint(discreel_shaders::polygon_vert, "kNoOutline"), kPolygonNoOutline);
    EXPECT_EQ(shader_uint(discreel_shaders::polygon_vert, "kNoSpinMarker"), kPolygonNoSpinMarker);
}

TEST(ShaderConstantsTest, PolygonQuadSizeMatchesThePointSpriteTest) {
    EXPECT_EQ(shader_float(discreel_shaders::polygon_vert, "kQuadMargin"), kPolygonQuadMargin);
}

TEST(ShaderConstantsTest, CapsuleFlagMatchesTheInstanceRecord) {
    EXPECT_EQ(shader_uint(discreel_shaders::capsule_frag, "kFlat"), kCapsuleFlat);
}

TEST(ShaderConstantsTest, AMissingOrMalformedConstantIsNotFound) {
    EXPECT_EQ(shader_uint("const uint kA = 1u;", "kB"), std::nullopt);
    EXPECT_EQ(shader_uint("const uint kA = x1u;", "kA"), std::nullopt);
    EXPECT_EQ(shader_uint("const uint kA = 7u;", "kA"), 7u);
    EXPECT_EQ(shader_float("const float kA = 1.5;", "kA"), 1.5f);
    EXPECT_EQ(shader_float("const float kA = 1.5x;", "kA"), std::nullopt);
}

}  // namespace
}  // namespace discreel::render
