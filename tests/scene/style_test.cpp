// The `style:` section and camera.follow: defaults, every key read, the shorthand forms.
#include <gtest/gtest.h>

#include "scene_test_support.hpp"

namespace discreel::scene {
namespace {

using testing::load_ok;
using testing::problems;
using Lines = std::vector<std::string>;

constexpr std::string_view two_discs = "discs:\n  - {id: cue, position: [1, 1], radius: 0.5}\n"
                                      "  - {position: [3, 1], radius: 0.5}\n";

TEST(Style, DefaultsKeepTheLookAndLeaveOverlaysOff) {
    const Scene s = load_ok("version: 1\n");
    EXPECT_TRUE(s.style.outline);
    EXPECT_TRUE(s.style.spin_marker);
    EXPECT_FALSE(s.style.velocity_arrows.enabled);
    EXPECT_FALSE(s.style.trails.enabled);
    EXPECT_FALSE(s.style.clock.enabled);
    EXPECT_FALSE(s.camera.follow.has_value());
    EXPECT_EQ(s.camera.follow_lag, 0.25);
}

TEST(Style, EveryKeyIsRead) {
    const Scene s = load_ok(
        std::string("version: 1\nstyle:\n"
                    "  outline: false\n  spin_marker: false\n"
                    "  velocity_arrows: {scale: 0.5, color: \"#ff000080\", width: 3}\n"
                    "  trails: {length: 2, fade: false, width: 0.25}\n"
                    "  clock: {corner: bottom-right, format: both, color: \"#00ff00\"}\n") +
        std::string(two_discs));
    EXPECT_FALSE(s.style.outline);
    EXPECT_FALSE(s.style.spin_marker);
    EXPECT_TRUE(s.style.velocity_arrows.enabled);
    EXPECT_EQ(s.style.velocity_arrows.scale, 0.5);
    EXPECT_EQ(s.style.velocity_arrows.color, (Color{255, 0, 0, 128}));
    EXPECT_EQ(s.style.velocity_arrows.width, 3);
    EXPECT_TRUE(s.style.trails.enabled);
    EXPECT_EQ(s.style.trails.length, 2);
    EXPECT_FALSE(s.style.trails.fade);
    EXPECT_EQ(s.style.trails.width, 0.25);
    EXPECT_TRUE(s.style.clock.enabled);
    EXPECT_EQ(s.style.clock.corner, Corner::bottom_right);
    EXPECT_EQ(s.style.clock.format, ClockFormat::both);
    EXPECT_EQ(s.style.clock.color, (Color{0, 255, 0, 255}));
}

TEST(Style, OverlaysTakeTrueFalseAnEmptyMappingOrEnabled) {
    const Scene s = load_ok("version: 1\nstyle:\n  velocity_arrows: true\n  trails:\n"
                            "  clock: {enabled: false, corner: top-right}\n");
    EXPECT_TRUE(s.style.velocity_arrows.enabled);
    EXPECT_EQ(s.style.velocity_arrows.scale, 0.25);
    EXPECT_TRUE(s.style.trails.enabled);
    EXPECT_EQ(s.style.trails.length, 0.5);
    EXPECT_FALSE(s.style.clock.enabled);
    EXPECT_EQ(s.style.clock.corner, Corner::top_right);
}

TEST(Style, DebugDrawingNamesWhatToDraw) {
    EXPECT_FALSE(load_ok("version: 1\n").style.debug.any());
    const Scene s = load_ok("version: 1\nstyle: {debug: [contacts, boxes, sleep]}\n");
    EXPECT_TRUE(s.style.debug.contacts);
    EXPECT_FALSE(s.style.debug.normals);
    EXPECT_FALSE(s.style.debug.impulses);
    EXPECT_TRUE(s.style.debug.boxes);
    EXPECT_FALSE(s.style.debug.joints);
    EXPECT_TRUE(s.style.debug.sleep);
    const Scene all =
        load_ok("version: 1\nstyle: {debug: [contacts, normals, impulses, boxes, joints, sleep]}\n");
    EXPECT_TRUE(all.style.debug.normals && all.style.debug.impulses && all.style.debug.joints);
}

TEST(Style, AnUnknownDebugDrawingSuggestsTheClosestOne) {
    EXPECT_EQ(problems("version: 1\nstyle:\n  debug: [contacts, normal, 3]\n"),
              (Lines{"s.yaml:3:21: style.debug[1]: expected one of contacts, normals, impulses, "
                     "boxes, joints, sleep, got 'normal'; did you mean 'normals'?",
                     "s.yaml:3:29: style.debug[2]: expected one of contacts, normals, impulses, "
                     "boxes, joints, sleep, got '3'"}));
    EXPECT_EQ(problems("version: 1\nstyle: {debug: contacts}\n"),
              Lines{"s.yaml:2:16: style.debug: expected a list (items starting with '- '), got "
                    "'contacts'"});
}

TEST(CameraFollow, NamesADiscByIdOrIndex) {
    Scene s = load_ok("version: 1\ncamera: {follow: cue, follow_lag: 0}\n" + std::string(two_discs));
    EXPECT_EQ(s.camera.follow, std::optional<std::size_t>{0});
    EXPECT_EQ(s.camera.follow_lag, 0);
    s = load_ok("version: 1\ncamera: {follow: 1}\n" + std::string(two_discs));
    EXPECT_EQ(s.camera.follow, std::optional<std::size_t>{1});
}

TEST(CameraFollow, AnUnknownIdSuggestsTheClosestOne) {
    EXPECT_EQ(problems("version: 1\ncamera: {follow: cure}\n" + std::string(two_discs)),
              Lines{"s.yaml:2:18: camera.follow: no disc has id 'cure'; did you mean 'cue'?"});
}

}  // namespace
}  // namespace discreel::scene
