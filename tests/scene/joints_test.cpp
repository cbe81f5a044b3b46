// `joints:` in a scene file: what loads, and every mistake at its line and column with the
// exact text a user sees.
#include <gtest/gtest.h>

#include "scene_test_support.hpp"

namespace discreel::scene {
namespace {

using testing::load_ok;
using testing::problems;
using Lines = std::vector<std::string>;
using Kind = physics::JointDef::Kind;

constexpr std::string_view bodies =
    "version: 1\n"
    "bodies:\n"
    "  - {id: arm, box: [2, 0.2], position: [1, 5]}\n"
    "  - {id: bob, circle: 0.2, position: [2, 3]}\n"
    "joints:\n";

TEST(Joints, EveryKindLoadsWithItsSettings) {
    const Scene scene = load_ok(std::string(bodies) +
                                "  - revolute: {b: arm, anchor: [0, 5], limits: [-0.5, 0.5],\n"
                                "               motor: {speed: 2, max_torque: 50}}\n"
                                "  - distance: {a: arm, b: 1, anchor_a: [2, 5], anchor_b: [2, 3],\n"
                                "               rope: true, spring: {frequency: 2, damping: 0.1}}\n"
                                "  - prismatic: {a: bob, anchor: [2, 3], axis: [0, 2],\n"
                                "                motor: {speed: 0.5, max_force: 100}}\n"
                                "  - weld: {a: arm, b: bob, anchor: [2, 4], collide: true}\n");
    ASSERT_EQ(scene.joints.size(), 4u);
    const physics::JointDef& pin = scene.joints[0];
    EXPECT_EQ(pin.kind, Kind::revolute);
    EXPECT_FALSE(pin.a.has_value());
    EXPECT_EQ(pin.b, 0u);
    EXPECT_EQ(pin.anchor_a.x, 0);
    EXPECT_EQ(pin.anchor_b.y, 5);
    ASSERT_TRUE(pin.limits.has_value());
    EXPECT_EQ((*pin.limits)[0], -0.5);
    ASSERT_TRUE(pin.motor.has_value());
    EXPECT_EQ(pin.motor->max_force, 50);
    const physics::JointDef& rope = scene.joints[1];
    EXPECT_EQ(rope.kind, Kind::distance);
    EXPECT_EQ(rope.a, 0u);
    EXPECT_EQ(rope.b, 1u);
    EXPECT_TRUE(rope.rope);
    EXPECT_LT(rope.length, 0);   // the anchors' distance at t = 0
    ASSERT_TRUE(rope.spring.has_value());
    EXPECT_EQ(rope.spring->frequency, 2);
    EXPECT_EQ(rope.spring->damping, 0.1);
    const physics::JointDef& slider = scene.joints[2];
    EXPECT_EQ(slider.kind, Kind::prismatic);
    EXPECT_EQ(slider.a, 1u);
    EXPECT_FALSE(slider.b.has_value());
    EXPECT_EQ(slider.axis.y, 2);
    EXPECT_EQ(slider.motor->speed, 0.5);
    EXPECT_TRUE(scene.joints[3].collide);
}

TEST(Joints, JoinedBodiesMayOverlapAtTheStart) {
    // Two capsules overlapping at their pin: joined, they never collide.
    const std::string links =
        "version: 1\n"
        "bodies:\n"
        "  - {capsule: {length: 1, radius: 0.1}, position: [0.5, 2]}\n"
        "  - {capsule: {length: 1, radius: 0.1}, position: [1.5, 2]}\n";
    EXPECT_EQ(problems(links + "joints:\n  - revolute: {a: 0, b: 1, anchor: [1, 2]}\n"), Lines{});
    EXPECT_EQ(problems(links + "joints:\n  - revolute: {a: 0, b: 1, anchor: [1, 2], collide: "
                               "true}\n"),
              Lines{"s.yaml:4:5: bodies[1]: body '1' overlaps body '0' (line 3) by 0.2 m at "
                    "t = 0"});
}

TEST(Joints, MistakesAreReportedAtTheirPlace) {
    EXPECT_EQ(problems(std::string(bodies) + "  - revolute: {a: arm, b: arm, anchor: [1, 1]}\n"),
              Lines{"s.yaml:6:27: joints[0].revolute.b: joins body 'arm' to itself; 'a' and 'b' "
                    "must be different bodies"});
    EXPECT_EQ(problems(std::string(bodies) + "  - revolut: {b: arm, anchor: [1, 1]}\n"),
              Lines{"s.yaml:6:5: joints[0]: unknown key 'revolut'; did you mean 'revolute'?"});
    EXPECT_EQ(problems(std::string(bodies) + "  - prismatic: {b: arm, anchor: [1, 1], axis: [0, 0]}\n"),
              Lines{"s.yaml:6:47: joints[0].prismatic.axis: the axis must not be [0, 0]; give its "
                    "direction"});
    EXPECT_EQ(problems(std::string(bodies) + "  - prismatic: {b: arm, anchor: [1, 1]}\n"),
              Lines{"s.yaml:6:16: joints[0].prismatic: missing required key 'axis'"});
    EXPECT_EQ(problems(std::string(bodies) + "  - revolute: {b: arm, anchor: [1, 1], limits: [1, -1]}\n"),
              Lines{"s.yaml:6:48: joints[0].revolute.limits: limits are [lower, upper], but 1 is "
                    "above -1"});
    EXPECT_EQ(problems(std::string(bodies) + "  - distance: {b: bobb, anchor_a: [1, 1], anchor_b: [2, 3]}\n"),
              Lines{"s.yaml:6:19: joints[0].distance.b: no body has id 'bobb'; did you mean 'bob'?"});
    EXPECT_EQ(problems(std::string(bodies) + "  - distance: {b: bob, anchor_a: [1, 1]}\n"),
              Lines{"s.yaml:6:15: joints[0].distance: missing required key 'anchor_b'"});
    EXPECT_EQ(problems(std::string(bodies) + "  - weld: {b: bob, anchor: [1, 1], lenght: 2}\n"),
              Lines{"s.yaml:6:36: joints[0].weld: unknown key 'lenght'; expected one of: a, b, "
                    "anchor, spring, collide, id"});
    EXPECT_EQ(problems(std::string(bodies) + "  - revolute: {anchor: [1, 1]}\n"),
              Lines{"s.yaml:6:15: joints[0].revolute: a joint needs a body: give 'b' (and 'a', "
                    "or leave it out to join 'b' to the world)"});
    EXPECT_EQ(problems(std::string(bodies) + "  - {revolute: {b: bob, anchor: [1, 1]}, "
                                             "weld: {b: arm, anchor: [1, 1]}}\n"),
              Lines{"s.yaml:6:42: joints[0]: one joint per entry; start another entry with '- "
                    "weld:'"});
    EXPECT_EQ(problems(std::string(bodies) + "  - distance: {b: bob, anchor_a: [2, 3], "
                                             "anchor_b: [2, 3]}\n"),
              Lines{"s.yaml:6:52: joints[0].distance.anchor_b: the anchors are the same point, "
                    "so the length would be 0; give 'length', or use a revolute joint to pin "
                    "them together"});
    EXPECT_EQ(problems(std::string(bodies) + "  - revolute: {id: pin, b: bob, anchor: [1, 1]}\n"
                                             "  - revolute: {id: pin, b: arm, anchor: [1, 1]}\n"),
              Lines{"s.yaml:7:20: joints[1].revolute.id: id 'pin' is already used by another "
                    "joint"});
    EXPECT_EQ(problems("version: 1\nbodies:\n  - random_polygons: {count: 2, region: [[0, 0], "
                       "[8, 8]], size: [0.2, 0.3], respawn_every: 2}\n    id: rocks\n"
                       "joints:\n  - revolute: {b: rocks.0, anchor: [1, 1]}\n"),
              Lines{"s.yaml:6:19: joints[0].revolute.b: body 'rocks.0' is replaced by its "
                    "generator's respawns; a joint cannot hold it"});
    EXPECT_EQ(problems(std::string(bodies) + "  - {}\n"),
              Lines{"s.yaml:6:5: joints[0]: a joint is one of revolute:, distance:, prismatic: "
                    "or weld:"});
    EXPECT_EQ(problems(std::string(bodies) + "  - distance: {b: bob, anchor_a: [1, 1], "
                                             "anchor_b: [2, 3], spring: {damping: 0.1}}\n"),
              Lines{"s.yaml:6:68: joints[0].distance.spring: missing required key 'frequency'"});
    EXPECT_EQ(problems(std::string(bodies) + "  - revolute: {b: bob, anchor: [1, 1], "
                                             "motor: {speed: 1, max_force: 3}}\n"),
              (Lines{"s.yaml:6:47: joints[0].revolute.motor: missing required key 'max_torque'",
                     "s.yaml:6:58: joints[0].revolute.motor: unknown key 'max_force'; expected "
                     "one of: speed, max_torque"}));
}

}  // namespace
}  // namespace discreel::scene

namespace discreel::scene {
namespace {

TEST(Kinematic, AGeneratorCannotBeKinematic) {
    EXPECT_EQ(testing::problems("version: 1\ndiscs:\n  - grid: {origin: [1, 1], count: [2, 1], "
                                "spacing: [1, 1], radius: 0.2}\n    kinematic: {velocity: [1, "
                                "0]}\n"),
              Lines{"s.yaml:4:5: discs[0]: 'kinematic' moves one disc or body, not a "
                    "generator's"});
}

TEST(Kinematic, AKinematicBodyLoadsItsMotion) {
    const Scene scene = testing::load_ok(
        "version: 1\n"
        "bodies:\n"
        "  - {id: sail, box: [4, 0.25], position: [6, 3], kinematic: {angular_velocity: 2}}\n"
        "  - {id: lift, box: [2, 0.2], position: [2, 1],\n"
        "     kinematic: {path: [[0.5, 2, 5, 0.3], [1, 2, 1, 0]], loop: true}}\n"
        "discs:\n"
        "  - {position: [9, 1], radius: 0.2, kinematic: {velocity: [1, 0.5]}}\n");
    ASSERT_EQ(scene.bodies.size(), 3u);
    const Body& disc = scene.bodies[0];   // discs come first
    ASSERT_TRUE(disc.kinematic.has_value());
    EXPECT_EQ(disc.kinematic->velocity.y, 0.5);
    const Body& sail = scene.bodies[1];
    ASSERT_TRUE(sail.kinematic.has_value());
    EXPECT_EQ(sail.kinematic->angular_velocity, 2);
    EXPECT_TRUE(sail.kinematic->path.empty());
    const Body& lift = scene.bodies[2];
    ASSERT_TRUE(lift.kinematic.has_value());
    ASSERT_EQ(lift.kinematic->path.size(), 2u);
    EXPECT_EQ(lift.kinematic->path[0].t, 0.5);
    EXPECT_EQ(lift.kinematic->path[0].angle, 0.3);
    EXPECT_TRUE(lift.kinematic->loop);
    EXPECT_FALSE(lift.is_static);
}

}  // namespace
}  // namespace discreel::scene

namespace discreel::scene {
namespace {

TEST(Filters, CategoriesAreBitsInTheOrderNamedAndSensorsLoad) {
    const Scene scene = testing::load_ok(
        "version: 1\n"
        "walls:\n"
        "  - {box: [[0, 0], [10, 10]], collides: [default, ghosts]}\n"
        "discs:\n"
        "  - {id: ghost, position: [2, 2], radius: 0.3, category: ghosts, collides: [walls]}\n"
        "  - {id: other, position: [2, 2.2], radius: 0.3}\n"   // overlaps the ghost: allowed
        "bodies:\n"
        "  - {id: gate, box: [2, 1], position: [5, 5], static: true, sensor: true}\n");
    EXPECT_EQ(scene.walls[0].category, 2u);
    EXPECT_EQ(scene.walls[0].collides, 1u | 4u);
    EXPECT_EQ(scene.bodies[0].category, 4u);
    EXPECT_EQ(scene.bodies[0].collides, 2u);
    EXPECT_EQ(scene.bodies[1].category, 1u);
    EXPECT_EQ(scene.bodies[1].collides, 0xffffffffu);
    EXPECT_TRUE(scene.bodies[2].sensor);
}

TEST(Filters, MistakesAreReportedAtTheirPlace) {
    std::string many = "version: 1\ndiscs:\n";
    for (int k = 0; k < 31; ++k) {
        many += "  - {position: [" + std::to_string(2 * k) + ", 1], radius: 0.5, category: c" +
                std::to_string(k) + "}\n";
    }
    EXPECT_EQ(testing::problems(many),
              Lines{"s.yaml:33:48: discs[30].category: 'c30' would be a 33rd category; a scene "
                    "may name at most 32 (default and walls included)"});
    EXPECT_EQ(testing::problems("version: 1\ndiscs:\n  - {position: [1, 1], radius: 0.5, "
                                "collides: walls}\n"),
              Lines{"s.yaml:3:47: discs[0].collides: expected a list (items starting with '- '), got "
                    "'walls'"});
    EXPECT_EQ(testing::problems("version: 1\ndiscs:\n  - {position: [1, 1], radius: 0.5, "
                                "category: [a]}\n"),
              Lines{"s.yaml:3:47: discs[0].category: expected a category name, got a list of "
                    "1 item"});
}

}  // namespace
}  // namespace discreel::scene
