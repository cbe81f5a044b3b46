#pragma once
// The determinism check's scene, its hash and the pinned value, shared by the GoogleTest suite
// (determinism_test.cpp) and the standalone check (determinism_check.cpp) that the `arch` tests
// build where GoogleTest is not at hand.
#include <cmath>
#include <cstdint>
#include <cstring>

#include "discreel/physics.hpp"
#include "scenes.hpp"

namespace discreel::physics::testing {

// What run_busy_scene() gives: the same on every target and build (ctest -L arch). It changes
// only when the solver does; update it deliberately then.
inline constexpr std::uint64_t busy_scene_hash = 15583903261220611190ull;

// A pile landing with a slanted segment, a peg, a flick and a grab. Every field of the pile is
// spelled out, so that the pinned hash does not follow PileDef's defaults.
inline WorldDef busy_scene() {
    WorldDef def = pile({.count = 500,
                         .radius = 0.2,
                         .spacing = 0.5,
                         .material = {.restitution = 0.6, .friction = 0.4},
                         .gravity = {0, -9.81},
                         .speed = 2.0,
                         .seed = 42});
    const Material material{.restitution = 0.6, .friction = 0.4};
    def.walls.push_back(segment({1, 5}, {8, 3}, 0.05, material));
    BodyDef peg = disc({6, 6}, {0, 0}, 0.3, 1.0, material);
    peg.is_static = true;
    def.bodies.push_back(peg);
    ThrowDef flick;
    flick.body = 3;
    flick.at = 0.5;
    flick.velocity = Vec2{40, 25};
    def.throws.push_back(flick);
    ThrowDef grab;
    grab.body = 100;
    grab.path = {{0.2, {3, 9}}, {0.8, {9, 9}}, {1.0, {5, 2}}};
    def.throws.push_back(grab);
    return def;
}

// FNV-1a over the bytes of every disc's state.
inline std::uint64_t state_hash(const World& world) {
    std::uint64_t h = 1469598103934665603ull;
    auto mix = [&h](double v) {
        std::uint64_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        for (int k = 0; k < 8; ++k) {
            h ^= (bits >> (8 * k)) & 0xff;
            h *= 1099511628211ull;
        }
    };
    for (const BodyState& s : world.bodies()) {
        mix(s.position.x);
        mix(s.position.y);
        mix(s.velocity.x);
        mix(s.velocity.y);
        mix(s.angle);
        mix(s.angular_velocity);
    }
    return h;
}

// What run_mixed_scene() gives, pinned like busy_scene_hash.
inline constexpr std::uint64_t mixed_scene_hash = 819653506250509134ull;

// Boxes, rounded hexagons, capsules and discs falling into a box past a slanted segment, with
// a flick and a grab: the manifold solver's determinism.
inline WorldDef mixed_scene() {
    WorldDef def;
    const Material material{.restitution = 0.5, .friction = 0.4};
    def.walls.push_back(box({0, 0}, {8, 12}, material));
    def.walls.push_back(segment({0.5, 6}, {5, 4}, 0.05, material));
    const std::vector<Vec2> hexagon{{0.25, 0}, {0.125, 0.2}, {-0.125, 0.2},
                                    {-0.25, 0}, {-0.125, -0.2}, {0.125, -0.2}};
    const Shape shapes[] = {*box_shape(0.5, 0.3), polygon_shape(hexagon, 0.02)->shape,
                            *capsule_shape(0.4, 0.1)};
    Rng rng(7);
    for (int k = 0; k < 80; ++k) {
        const Vec2 at{0.5 + 0.7 * (k % 10), 6.5 + 0.7 * (k / 10)};
        BodyDef d = k % 4 == 3 ? disc(at, {}, 0.2, 0.125, material)
                               : body(shapes[k % 4], at, 1.0, material);
        d.angle = rng.uniform(0, 3);
        d.velocity = {rng.uniform(-2, 2), rng.uniform(-2, 2)};
        d.angular_velocity = rng.uniform(-4, 4);
        def.bodies.push_back(d);
    }
    ThrowDef flick;
    flick.body = 5;
    flick.at = 0.5;
    flick.velocity = Vec2{30, 10};
    def.throws.push_back(flick);
    ThrowDef grab;
    grab.body = 2;
    grab.path = {{0.3, {2, 3}}, {0.9, {6, 3}}, {1.2, {4, 8}}};
    def.throws.push_back(grab);
    return def;
}

inline std::uint64_t run_mixed_scene() {
    World world(mixed_scene());
    run_for(world, 2.0);
    return state_hash(world);
}

// What run_heavy_light_scene() gives, pinned like busy_scene_hash.
inline constexpr std::uint64_t heavy_light_scene_hash = 14595984683914181768ull;

// 64 plain discs in a box, every other one 1 000 times heavier, thrown, landing and settling:
// the disc solver's direct islands (src/physics/disc_islands.hpp; some 300 collisions and as
// many resting solves), whose double-precision solves must give the same bits too.
inline WorldDef heavy_light_scene() {
    WorldDef def;
    const Material material{.restitution = 0.5, .friction = 0.5};
    def.walls.push_back(box({0, 0}, {10, 10}, material));
    Rng rng(11);
    for (int k = 0; k < 64; ++k) {
        const double angle = rng.uniform(0, 6.283185307179586);
        const Vec2 at{(1 + k % 8) * 1.1, (1 + k / 8) * 1.1};
        def.bodies.push_back(disc(at, {2 * std::cos(angle), 2 * std::sin(angle)}, 0.4,
                                 k % 2 ? 1000.0 : 1.0, material));
    }
    return def;
}

inline std::uint64_t run_heavy_light_scene() {
    World world(heavy_light_scene());
    run_for(world, 2.0);
    return state_hash(world);
}

// What run_resting_scene() gives, pinned like busy_scene_hash.
inline constexpr std::uint64_t resting_scene_hash = 16339297378939358578ull;

// An 8-row pyramid of boxes with a capsule and a rounded hexagon beside it, all landing from
// a millimetre up and resting for two seconds, awake (sleep off): the manifold solver's steps
// that keep their contacts from the step before (BodySolverDef::keep_contacts) as well as
// those that make them.
inline WorldDef resting_scene() {
    WorldDef def;
    def.sleep = false;
    const Material material{.restitution = 0.2, .friction = 0.6};
    def.walls.push_back(box({-10, 0}, {10, 20}, material));
    for (int row = 0; row < 8; ++row) {
        const int n = 8 - row;
        for (int i = 0; i < n; ++i) {
            def.bodies.push_back(body(*box_shape(1, 1), {i - (n - 1) / 2.0, 0.501 + row}, 1.0,
                                      material));
        }
    }
    const std::vector<Vec2> hexagon{{0.25, 0}, {0.125, 0.2}, {-0.125, 0.2},
                                    {-0.25, 0}, {-0.125, -0.2}, {0.125, -0.2}};
    def.bodies.push_back(body(*capsule_shape(0.8, 0.1), {-6, 0.101}, 1.0, material));
    def.bodies.push_back(body(polygon_shape(hexagon, 0.02)->shape, {6, 0.221}, 1.0, material));
    return def;
}

inline std::uint64_t run_resting_scene() {
    World world(resting_scene());
    run_for(world, 2.0);
    return state_hash(world);
}

// What run_joint_scene() gives, pinned like busy_scene_hash.
inline constexpr std::uint64_t joint_scene_hash = 465108837284810233ull;

// Every kind of joint at work beside falling boxes: a chain of capsules from a pin, a bob on a
// rope, a box on a damped spring, a motor driving a slider into its limit, a turning paddle
// with a motor, and a welded pair; the manifold solver's joints and their determinism.
inline WorldDef joint_scene() {
    WorldDef def;
    const Material material{.restitution = 0.3, .friction = 0.5};
    def.walls.push_back(box({0, 0}, {16, 12}, material));
    const auto joint = [&](JointDef::Kind kind, std::optional<std::size_t> a, std::size_t b,
                           Vec2 anchor, Vec2 anchor_b = {}) {
        JointDef j;
        j.kind = kind;
        j.a = a;
        j.b = b;
        j.anchor_a = anchor;
        j.anchor_b = kind == JointDef::Kind::distance ? anchor_b : anchor;
        def.joints.push_back(j);
        return &def.joints.back();
    };
    const auto add = [&](BodyDef d) {
        def.bodies.push_back(d);
        return def.bodies.size() - 1;
    };
    for (int i = 0; i < 8; ++i) {   // the chain, level from (2, 10)
        const std::size_t link = add(body(*capsule_shape(0.4, 0.06), {2.2 + 0.4 * i, 10}, 2.0,
                                          material));
        joint(JointDef::Kind::revolute, i == 0 ? std::nullopt : std::optional(link - 1), link,
              {2.0 + 0.4 * i, 10});
    }
    const std::size_t bob = add(body(circle_shape(0.2), {7, 7}, 1.0, material));
    joint(JointDef::Kind::distance, std::nullopt, bob, {6, 10}, {7, 7})->rope = true;
    const std::size_t weight = add(body(*box_shape(0.5, 0.5), {9, 6}, 1.0, material));
    joint(JointDef::Kind::distance, std::nullopt, weight, {9, 9}, {9, 6})->spring =
        SpringDef{1.5, 0.2};
    const std::size_t cart = add(body(*box_shape(0.8, 0.3), {11, 2}, 1.0, material));
    JointDef* slider = joint(JointDef::Kind::prismatic, std::nullopt, cart, {11, 2});
    slider->axis = {1, 0.2};
    slider->limits = std::array<double, 2>{-1.0, 1.5};
    slider->motor = JointDef::Motor{1.0, 50.0};
    const std::size_t paddle = add(body(*box_shape(2.0, 0.2), {13, 7}, 1.0, material));
    joint(JointDef::Kind::revolute, std::nullopt, paddle, {13, 7})->motor =
        JointDef::Motor{2.0, 100.0};
    const std::size_t left = add(body(*box_shape(0.6, 0.6), {4.7, 4}, 1.0, material));
    const std::size_t right = add(body(*box_shape(0.6, 0.6), {5.3, 4}, 1.0, material));
    joint(JointDef::Kind::weld, left, right, {5.0, 4.0});
    for (int i = 0; i < 6; ++i) {   // boxes falling onto the chain and the paddle
        add(body(*box_shape(0.4, 0.3), {3 + 1.9 * i, 11.3}, 1.0, material));
    }
    return def;
}

inline std::uint64_t run_joint_scene() {
    World world(joint_scene());
    run_for(world, 2.0);
    return state_hash(world);
}

// The busy scene's state after two seconds, hashed.
inline std::uint64_t run_busy_scene() {
    World world(busy_scene());
    run_for(world, 2.0);
    return state_hash(world);
}

}  // namespace discreel::physics::testing
