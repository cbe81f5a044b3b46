// `--set KEY=VALUE`: values put into the scene before it is read, checked like the file's own,
// their problems named by the option.
#include <gtest/gtest.h>

#include "scene_test_support.hpp"

namespace discreel::scene {
namespace {

using Lines = std::vector<std::string>;

constexpr std::string_view two_discs =
    "version: 1\n"
    "video: {size: [320, 180], fps: 10, duration: 1}\n"
    "discs:\n"
    "  - {position: [0, 1], radius: 0.2}\n"
    "  - {position: [1, 1], radius: 0.2}\n";

std::vector<Override> parse_all(const std::vector<std::string>& texts) {
    std::vector<Override> out;
    for (const std::string& text : texts) {
        auto parsed = parse_override(text);
        EXPECT_TRUE(parsed.ok()) << text;
        if (parsed) out.push_back(*parsed);
    }
    return out;
}

LoadResult load_with(std::string_view yaml, const std::vector<std::string>& sets) {
    const std::vector<Override> overrides = parse_all(sets);
    return load_scene_text(yaml, "s.yaml", {}, std::nullopt, overrides);
}

Lines problems_with(std::string_view yaml, const std::vector<std::string>& sets) {
    Lines lines;
    for (const Diagnostic& d : load_with(yaml, sets).diagnostics) lines.push_back(d.to_string());
    return lines;
}

TEST(Overrides, SetScalarsListsAndListItemsAsTheFileWould) {
    const LoadResult loaded =
        load_with(two_discs, {"physics.seed=3", "video.size=[128,96]", "discs.1.radius=0.3",
                              "video.background=\"#102030\""});
    ASSERT_TRUE(loaded.ok());
    EXPECT_EQ(loaded.scene.physics.seed, 3u);
    EXPECT_EQ(loaded.scene.video.width, 128);
    EXPECT_EQ(loaded.scene.video.height, 96);
    EXPECT_DOUBLE_EQ(loaded.scene.bodies.at(1).radius, 0.3);
    EXPECT_DOUBLE_EQ(loaded.scene.bodies.at(0).radius, 0.2);
    EXPECT_EQ(loaded.scene.video.background, (Color{0x10, 0x20, 0x30, 0xff}));
}

TEST(Overrides, TheLastOfTwoForOneKeyWins) {
    const LoadResult loaded = load_with(two_discs, {"video.fps=20", "video.fps=25"});
    ASSERT_TRUE(loaded.ok());
    EXPECT_EQ(loaded.scene.video.fps, 25);
}

TEST(Overrides, AColourNeedsNoQuotesOnTheCommandLine) {
    const LoadResult loaded = load_with(two_discs, {"discs.0.color=#ff0000"});
    ASSERT_TRUE(loaded.ok());
    EXPECT_EQ(loaded.scene.bodies.at(0).color, (Color{0xff, 0, 0, 0xff}));
}

TEST(Overrides, ProblemsNameTheOptionNotALineOfTheFile) {
    EXPECT_EQ(problems_with(two_discs, {"physics.sede=3"}),
              Lines{"--set physics.sede=3: physics: unknown key 'sede'; did you mean 'seed'?"});
    EXPECT_EQ(problems_with(two_discs, {"phyics.seed=3"}),
              Lines{"--set phyics.seed=3: unknown top-level key 'phyics'; did you mean "
                    "'physics'?"});
    EXPECT_EQ(problems_with(two_discs, {"discs.0.radius=abc"}),
              Lines{"--set discs.0.radius=abc: discs[0].radius: expected a number, got 'abc'"});
    EXPECT_EQ(problems_with(two_discs, {"discs.0.radius="}),
              Lines{"--set discs.0.radius=: discs[0].radius: expected a number, got ''"});
}

TEST(Overrides, PathsThatLeadNowhereSayWhy) {
    EXPECT_EQ(problems_with(two_discs, {"discs.7.radius=0.3"}),
              Lines{"--set discs.7.radius=0.3: 'discs' is a list of 2 items, numbered from 0; "
                    "it has no item '7'"});
    EXPECT_EQ(problems_with(two_discs, {"video.fps.x=2"}),
              Lines{"--set video.fps.x=2: 'video.fps' is a single value, not a mapping or a "
                    "list: it has no 'x'"});
    EXPECT_EQ(problems_with(two_discs, {"video..fps=2"}),
              Lines{"--set video..fps=2: the key 'video..fps' has an empty part; write a dotted "
                    "path such as physics.seed or discs.0.radius"});
    EXPECT_EQ(problems_with(two_discs, {"video.size=[1,2"}),
              Lines{"--set video.size=[1,2: invalid YAML in the value: end of sequence flow not "
                    "found"});
}

// A value over several lines shifts nothing: the next override's problem is still its own.
TEST(Overrides, AValueOverSeveralLinesKeepsTheOthersApart) {
    const LoadResult loaded = load_with(two_discs, {"video.size=[64,\n  48]", "video.fps=25"});
    ASSERT_TRUE(loaded.ok());
    EXPECT_EQ(loaded.scene.video.width, 64);
    EXPECT_EQ(loaded.scene.video.height, 48);
    EXPECT_EQ(loaded.scene.video.fps, 25);
    EXPECT_EQ(problems_with(two_discs, {"video.size=[64,\n  48]", "video.fps=fast"}),
              Lines{"--set video.fps=fast: video.fps: expected a whole number, got 'fast'"});
}

TEST(Overrides, FileProblemsKeepTheirLinesAndComeFirst) {
    const std::string bad = std::string(two_discs) + "walls: 3\n";
    const Lines lines = problems_with(bad, {"physics.sede=3"});
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_EQ(lines[0].rfind("s.yaml:6:8: walls:", 0), 0u) << lines[0];
    EXPECT_EQ(lines[1].rfind("--set physics.sede=3:", 0), 0u) << lines[1];
}

TEST(Overrides, WithoutAnEqualsSignTheOptionIsRefused) {
    const auto parsed = parse_override("physics.seed");
    ASSERT_FALSE(parsed.ok());
    EXPECT_EQ(parsed.error().message,
              "--set physics.seed: expected KEY=VALUE with KEY a dotted path into the scene, "
              "e.g. physics.seed=3 or discs.0.radius=0.3");
    EXPECT_FALSE(parse_override("=3").ok());
}

}  // namespace
}  // namespace discreel::scene
