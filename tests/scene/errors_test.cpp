// Each kind of problem, with the exact text a user sees. The messages are a user interface:
// a change to one of them should be a deliberate change to this file.
#include <gtest/gtest.h>

#include "scene_test_support.hpp"

namespace discreel::scene {
namespace {

using testing::problems;
using Lines = std::vector<std::string>;

TEST(Errors, YamlSyntaxErrorsPointAtTheParserPosition) {
    EXPECT_EQ(problems("version: 1\nvideo: {fps: 30\n"),
              Lines{"s.yaml:3:1: invalid YAML: end of map flow not found"});
}

TEST(Errors, UnknownKeysSuggestTheClosestKnownKey) {
    EXPECT_EQ(problems("version: 1\nvideo:\n  sise: [640, 480]\n"),
              Lines{"s.yaml:3:3: video: unknown key 'sise'; did you mean 'size'?"});
    EXPECT_EQ(problems("version: 1\ndisks: []\n"),
              Lines{"s.yaml:2:1: unknown top-level key 'disks'; did you mean 'discs'?"});
}

TEST(Errors, UnknownKeysWithNothingCloseListTheKnownOnes) {
    EXPECT_EQ(problems("version: 1\ncamera:\n  zoom: 2\n"),
              Lines{"s.yaml:3:3: camera: unknown key 'zoom'; expected one of: center, height, "
                    "follow, follow_lag, keys, ease"});
}

TEST(Errors, WrongTypesSayWhatWasExpectedAndWhatWasFound) {
    EXPECT_EQ(problems("version: 1\nvideo:\n  fps: fast\n  size: 640\n"),
              (Lines{"s.yaml:3:8: video.fps: expected a whole number, got 'fast'",
                     "s.yaml:4:9: video.size: expected a list of two numbers [width, height], "
                     "got '640'"}));
    EXPECT_EQ(problems("version: 1\ndiscs:\n  - {position: [1, 2, 3], radius: 0.5}\n"),
              Lines{"s.yaml:3:16: discs[0].position: expected a list of two numbers [x, y], "
                    "got a list of 3 items"});
    EXPECT_EQ(problems("version: 1\nphysics:\n  rate:\n"),
              Lines{"s.yaml:3:3: physics.rate: expected a whole number, got nothing"});
}

TEST(Errors, ColoursAreHexOrCssNamesAndAnUnquotedHashIsExplained) {
    // CSS names in any case and the short hex form are colours.
    EXPECT_EQ(problems("version: 1\nvideo:\n  background: navy\ndiscs:\n"
                       "  - {position: [1, 1], radius: 0.2, color: SteelBlue}\n"
                       "  - {position: [3, 1], radius: 0.2, color: \"#f80\"}\n"),
              Lines{});
    const Scene named = testing::load_ok("version: 1\ndiscs:\n"
                                "  - {position: [1, 1], radius: 0.2, color: SteelBlue}\n"
                                "  - {position: [3, 1], radius: 0.2, color: \"#f80\"}\n");
    EXPECT_EQ(named.bodies[0].color, (Color{0x46, 0x82, 0xb4, 0xff}));
    EXPECT_EQ(named.bodies[1].color, (Color{0xff, 0x88, 0x00, 0xff}));
    EXPECT_EQ(problems("version: 1\nvideo:\n  background: nvy\n"),
              Lines{"s.yaml:3:15: video.background: 'nvy' is not a colour name; did you mean "
                    "'navy'?"});
    EXPECT_EQ(problems("version: 1\nvideo:\n  background: nothing-like-a-colour\n"),
              Lines{"s.yaml:3:15: video.background: expected a colour like \"#rrggbb\", "
                    "\"#rrggbbaa\", \"#rgb\" or a CSS name (\"steelblue\"), got "
                    "'nothing-like-a-colour'"});
    EXPECT_EQ(problems("version: 1\nvideo:\n  background: #000000\n"),
              Lines{"s.yaml:3:3: video.background: expected a colour like \"#rrggbb\", "
                    "\"#rrggbbaa\", \"#rgb\" or a CSS name (\"steelblue\"), got nothing (put the "
                    "colour in quotes: YAML reads an unquoted '#' as the start of a comment)"});
}

// In flow style the comment also swallows the closing bracket; the colour is pointed at and the
// file's other problems are still found. A comment that merely looks like hex is left alone.
TEST(Errors, AnUnquotedColourInFlowStyleIsPointedAt) {
    EXPECT_EQ(problems("version: 1\ndiscs:\n  - {position: [1, 1], radius: 0.2, color: #ff0000}\n"
                       "  - {position: [3, 1], radius: 0}\n"),
              (Lines{"s.yaml:3:44: a colour in {...} or [...] must be quoted: YAML reads an "
                     "unquoted '#' as the start of a comment, which hides the closing bracket; "
                     "write color: \"#rrggbb\"",
                     "s.yaml:4:32: discs[1].radius: must be greater than 0, got 0"}));
    EXPECT_EQ(problems("version: 1\ndiscs: [\n  {position: [1, 1], radius: 0.2},  #add\n]\n"),
              Lines{});
}

TEST(Errors, ValuesOutOfRangeStateTheRange) {
    EXPECT_EQ(problems("version: 1\nvideo: {fps: 0, duration: 4000}\n"
                       "physics: {rate: 200000, restitution: -0.5, friction: -1}\n"),
              (Lines{"s.yaml:2:14: video.fps: must be between 1 and 240, got 0",
                     "s.yaml:2:27: video.duration: must be greater than 0 and at most 3600 "
                     "seconds, got 4000 (raise the limit with --max-duration)",
                     "s.yaml:3:17: physics.rate: must be between 1 and 100000, got 200000",
                     "s.yaml:3:38: physics.restitution: must be between 0 and 1, got -0.5",
                     "s.yaml:3:54: physics.friction: must be at least 0, got -1"}));
    EXPECT_EQ(problems("version: 1\nphysics: {substeps: 0, iterations: 101}\n"),
              (Lines{"s.yaml:2:21: physics.substeps: must be between 1 and 1000, got 0",
                     "s.yaml:2:36: physics.iterations: must be between 1 and 100, got 101"}));
    EXPECT_EQ(problems("version: 1\nphysics: {iterations: 2.5}\n"),
              Lines{"s.yaml:2:23: physics.iterations: expected a whole number, got '2.5'"});
    EXPECT_EQ(problems("version: 1\nphysics: {sleep: 1}\n"),
              Lines{"s.yaml:2:18: physics.sleep: expected true or false, got '1'"});
    EXPECT_EQ(problems("version: 1\ndiscs:\n  - {position: [0, 0], radius: -1, density: 0}\n"),
              (Lines{"s.yaml:3:32: discs[0].radius: must be greater than 0, got -1",
                     "s.yaml:3:45: discs[0].density: must be greater than 0, got 0"}));
}

// An odd side is a scene's to choose: stills and GIFs take it, and a video output refuses it
// when it is asked for (CliGLTest.OddSizesAreForStillsGifsAndFullColourVideo).
TEST(Errors, OddFrameSizesAreAScenesToChoose) {
    EXPECT_EQ(problems("version: 1\nvideo:\n  size: [641, 481]\n"), Lines{});
}

TEST(Errors, SizesOutsideTheLimits) {
    EXPECT_EQ(problems("version: 1\nvideo:\n  size: [10, 5000]\n"),
              (Lines{"s.yaml:3:10: video.size: width must be between 16 and 7680, got 10",
                     "s.yaml:3:14: video.size: height must be between 16 and 4320, got 5000"}));
}

TEST(Errors, MissingRequiredKeys) {
    EXPECT_EQ(problems("video: {fps: 30}\n"),
              Lines{"s.yaml:1:1: missing required key 'version'; start the file with "
                    "'version: 1'"});
    EXPECT_EQ(problems("version: 1\ndiscs:\n  - velocity: [1, 0]\n"),
              (Lines{"s.yaml:3:5: discs[0]: missing required key 'position'",
                     "s.yaml:3:5: discs[0]: missing required key 'radius'"}));
}

TEST(Errors, ALaterFormatVersionIsTheOnlyProblemReported) {
    EXPECT_EQ(problems("version: 3\nfancy: yes\n"),
              Lines{"s.yaml:1:10: version: this file is format version 3, but this build of "
                    "discreel reads only version 1"});
}

TEST(Errors, MassTogetherWithDensity) {
    EXPECT_EQ(problems("version: 1\ndiscs:\n  - {position: [0, 0], radius: 1, density: 2, "
                       "mass: 3}\n"),
              Lines{"s.yaml:3:47: discs[0]: give either 'mass' or 'density', not both"});
}

TEST(Errors, DuplicateIdsPointAtTheSecondAndNameTheFirstLine) {
    EXPECT_EQ(problems("version: 1\ndiscs:\n  - {id: a, position: [0, 0], radius: 0.5}\n"
                       "  - {id: a, position: [2, 0], radius: 0.5}\n"),
              Lines{"s.yaml:4:10: discs[1].id: id 'a' is already used by the disc on line 3"});
}

TEST(Errors, ThrowsNamingMissingDiscs) {
    const std::string discs = "version: 1\ndiscs:\n  - {id: striker, position: [0, 0], radius: "
                              "0.5}\nthrows:\n";
    EXPECT_EQ(problems(discs + "  - {disc: stiker, velocity: [1, 0]}\n"),
              Lines{"s.yaml:5:12: throws[0].disc: no disc has id 'stiker'; did you mean "
                    "'striker'?"});
    EXPECT_EQ(problems(discs + "  - {disc: 1, velocity: [1, 0]}\n"),
              Lines{"s.yaml:5:12: throws[0].disc: there is no disc 1; the scene has 1 disc, "
                    "numbered 0"});
}

TEST(Errors, DiscsOverlappingAtTheStartNameBoth) {
    EXPECT_EQ(problems("version: 1\ndiscs:\n  - {id: a, position: [0, 0], radius: 0.5}\n"
                       "  - {id: b, position: [0.75, 0], radius: 0.5}\n"),
              Lines{"s.yaml:4:5: discs[1]: disc 'b' overlaps disc 'a' (line 3) by 0.25 m at "
                    "t = 0"});
}

TEST(Errors, GoldenFramesOutsideTheClip) {
    EXPECT_EQ(problems("version: 1\nvideo: {fps: 10, duration: 1}\ngolden: {frames: [9, 10]}\n"),
              Lines{"s.yaml:3:22: golden.frames[1]: frame 10 is outside the clip; it has 10 "
                    "frames, numbered 0 to 9"});
}

TEST(Errors, NonFiniteNumbers) {
    EXPECT_EQ(problems("version: 1\ncamera: {height: .inf}\n"),
              Lines{"s.yaml:2:18: camera.height: must be a finite number, got '.inf'"});
}

TEST(Errors, ProtectiveLimitsStateTheLimit) {
    EXPECT_EQ(problems("version: 1\ndiscs:\n  - random: {count: 100001, region: [[0, 0], [1, 1]], "
                       "radius: 0.1}\n"),
              Lines{"s.yaml:3:21: discs[0].random.count: must be between 1 and 100000, got "
                    "100001"});
}

TEST(Errors, RandomDiscsThatDoNotFit) {
    EXPECT_EQ(problems("version: 1\ndiscs:\n  - random: {count: 3, region: [[0, 0], [1, 1]], "
                       "radius: 0.4}\n"),
              Lines{"s.yaml:3:13: discs[0].random: could place only 1 of 3 discs without "
                    "overlap; make the region larger, the discs smaller or the count lower"});
}

TEST(Errors, EveryProblemIsReportedInFileOrder) {
    // Sections are read in dependency order (physics before discs), yet the report follows
    // the file.
    EXPECT_EQ(problems(R"(version: 1
discs:
  - {position: [0, 0], radius: 0, colour: "#ffffff"}
video:
  fps: 1000
physics:
  restitution: 2
)"),
              (Lines{"s.yaml:3:32: discs[0].radius: must be greater than 0, got 0",
                     "s.yaml:3:35: discs[0]: unknown key 'colour'; did you mean 'color'?",
                     "s.yaml:5:8: video.fps: must be between 1 and 240, got 1000",
                     "s.yaml:7:16: physics.restitution: must be between 0 and 1, got 2"}));
}

TEST(Errors, AFloodOfProblemsIsCutShortWithACount) {
    std::string yaml = "version: 1\ndiscs:\n";
    for (int i = 0; i < 150; ++i) yaml += "  - {position: [0, 0], radius: -1}\n";
    const auto lines = problems(yaml);
    ASSERT_EQ(lines.size(), 101u);
    EXPECT_EQ(lines[0], "s.yaml:3:32: discs[0].radius: must be greater than 0, got -1");
    EXPECT_EQ(lines[100], "s.yaml:103:32: too many problems; 50 more not shown");
}

// The protective limits are the caller's to set: the CLI's --max-bodies and friends.
TEST(Errors, LimitsAreTheCallersToRaise) {
    const std::string text = "version: 1\nvideo: {duration: 5000}\n"
                             "discs:\n  - grid: {count: [400, 300], radius: 0.01, spacing: [0.03, 0.03]}\n";
    const LoadResult strict = load_scene_text(text, "s.yaml");
    ASSERT_EQ(strict.diagnostics.size(), 2u);
    EXPECT_EQ(strict.diagnostics[0].to_string(),
              "s.yaml:2:19: video.duration: must be greater than 0 and at most 3600 seconds, got "
              "5000 (raise the limit with --max-duration)");
    EXPECT_EQ(strict.diagnostics[1].to_string(),
              "s.yaml:4:19: discs[0].grid.count: 400 x 300 = 120000 discs is more than the limit "
              "of 100000 bodies (raise it with --max-bodies)");

    const LoadResult raised =
        load_scene_text(text, "s.yaml", Limits{.bodies = 200'000, .duration = 6000});
    EXPECT_TRUE(raised.ok()) << raised.diagnostics.front().to_string();
    EXPECT_EQ(raised.scene.bodies.size(), 120'000u);

    const LoadResult tiny = load_scene_text(text, "s.yaml", Limits{.file_bytes = 10});
    ASSERT_EQ(tiny.diagnostics.size(), 1u);
    EXPECT_EQ(tiny.diagnostics[0].to_string(),
              "s.yaml: the file is too large (" + std::to_string(text.size()) +
                  " bytes); the limit is 10 bytes (raise it with --max-scene-bytes)");
}

}  // namespace
}  // namespace discreel::scene
