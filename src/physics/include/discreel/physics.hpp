#pragma once
// 2-D rigid bodies (discs, and convex shapes: shapes.hpp) against static walls, stepped at a
// fixed rate. Plain definitions in, plain state out: no YAML, GL or FFmpeg here. Usage:
//     physics::World world(def);
//     while (world.time() < t_end) world.step();
//     for (const auto& d : world.bodies()) ...
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "discreel/shapes.hpp"
#include "discreel/vec2.hpp"

namespace discreel::physics {

// Collision categories (BodyDef::category, collides): one bit each; a body's and a wall's by
// default, and the bits of every category.
inline constexpr std::uint32_t default_category = 1, walls_category = 2;
inline constexpr std::uint32_t all_categories = 0xffffffffu;

// Whether a body's or wall's filter differs from its kind's default (it meets everything).
inline bool filters(std::uint32_t category, std::uint32_t collides, bool wall) {
    return category != (wall ? walls_category : default_category) || collides != all_categories;
}

// A kinematic body's motion: it moves as told, whatever touches it, and pushes what it meets
// as an infinitely heavy body does (a moving platform, a windmill's sails).
struct KinematicDef {
    struct Pose {
        double t = 0.0;            // seconds
        Vec2 position;             // metres
        double angle = 0.0;        // radians
    };
    Vec2 velocity;                 // m/s, kept for ever (no path)
    double angular_velocity = 0.0; // rad/s, kept for ever (no path)
    // When not empty: poses to pass through at their times, straight from one to the next
    // (from where the body starts to the first, if that is after t = 0); after the last it
    // stays there, or with `loop` starts again from the path's beginning.
    std::vector<Pose> path;
    bool loop = false;
};

// A body: a disc of `radius`, or, with `shape`, any convex shape, all in one numbering. A
// world whose bodies are all plain discs is stepped by the disc solver; one with any shape by
// the manifold solver (docs/physics.md, uses_manifold_solver).
struct BodyDef {
    Vec2 position;                 // metres; the centroid for a shape
    Vec2 velocity;                 // m/s
    double angle = 0.0;            // radians
    double angular_velocity = 0.0; // rad/s, counter-clockwise positive
    double radius = 0.5;           // metres, > 0; ignored when `shape` is set
    double mass = 1.0;             // kg, > 0; ignored for static bodies
    std::optional<Shape> shape;    // unset: a disc of `radius`
    double restitution = 0.8;      // coefficient of restitution, 0..1
    double friction = 0.2;         // Coulomb coefficient, >= 0
    bool is_static = false;        // a fixed peg: collides, never moves
    std::optional<KinematicDef> kinematic;   // moved as told, not by what touches it
    // Collision filtering: two things touch only where each one's category is among the
    // other's `collides` bits (docs/physics.md, "Filters and sensors").
    std::uint32_t category = default_category;    // one bit
    std::uint32_t collides = all_categories;      // bits of the categories it meets
    // A sensor pushes nothing and is pushed by nothing: its overlaps with the bodies it meets
    // are reported as events (ContactEvent::Kind::begin and end).
    bool sensor = false;
};

struct WallDef {
    enum class Shape {
        box,      // closed container: a..b are the min and max corners, bodies kept inside
        segment,  // capsule from a to b
    };
    Shape shape = Shape::segment;
    Vec2 a;                        // metres
    Vec2 b;                        // metres
    double thickness = 0.02;       // metres, full thickness
    double restitution = 0.8;
    double friction = 0.2;
    std::uint32_t category = walls_category;
    std::uint32_t collides = all_categories;
};

// How a contact's restitution and friction come from its two materials' (docs/physics.md,
// "Materials"): the larger, the smaller, the geometric mean sqrt(a b), or the product.
enum class MixRule { max, min, mean, product };
double mix(MixRule rule, double a, double b);
struct Mixing {
    MixRule restitution = MixRule::max;   // the bouncier material wins
    MixRule friction = MixRule::mean;     // as Box2D: ice on anything slides
    double restitution_of(double a, double b) const { return mix(restitution, a, b); }
    double friction_of(double a, double b) const { return mix(friction, a, b); }
};
// The default rules.
double mix_restitution(double a, double b);
double mix_friction(double a, double b);

struct Waypoint {
    double t = 0.0;                // seconds
    Vec2 position;                 // metres
};

struct ThrowDef {
    std::size_t body = 0;          // index into WorldDef::bodies
    double at = 0.0;               // seconds; flick time
    std::optional<Vec2> velocity;  // m/s; a flick when set
    std::vector<Waypoint> path;    // a grab when non-empty
    std::optional<Vec2> release;   // m/s; release velocity of a grab (default: path's)
};

// The range of masses and speeds in which a crowd of bodies (every body touching several at
// once) is measured to stay apart with energy not rising beyond rounding (docs/physics.md,
// "Limits"; bench/limits_bench.cpp, tests/physics/extremes_test.cpp). Walls hold at any mass
// ratio and speed, and small groups of bodies in contact hold at any mass ratio (their
// contacts are solved together); beyond it, a heavy body in a crowd sinks into light ones and
// fast bodies of a crowd overlap. Scenes warn against it.
struct Envelope {
    // Heaviest / lightest moving body of a crowd that stays apart.
    double crowd_mass_ratio = 1000;
    // A crowd is at least this many moving bodies: fewer meet in small groups, which both
    // solvers' direct stages hold at any mass ratio and speed (docs/physics.md, "Limits").
    std::size_t crowd_bodies = 8;
    // Radii of the smallest moving body per step at equal masses: the disc solver times every
    // impact between moving discs; the manifold solver (any body with a shape) times those of
    // fast bodies too, but a crowd of them still sinks in where the iterations share out
    // contacts touching at a step's start (docs/physics.md, "Limits").
    double disc_radii_per_step = 10;
    double body_radii_per_step = 2;

    // Radii of the smallest moving body a body of a crowd may travel per physics step when the
    // moving bodies' masses differ by `mass_ratio`: 10 / ratio^(2/3) for the disc solver (a
    // light disc between heavy ones needs about pi sqrt(ratio) impacts per squeeze, out of the
    // impact stage's budget), 2 / sqrt(ratio) for the manifold solver.
    double radii_per_step(double mass_ratio, bool manifold) const {
        return manifold ? body_radii_per_step / std::sqrt(mass_ratio)
                        : disc_radii_per_step / std::cbrt(mass_ratio * mass_ratio);
    }
};

inline constexpr Envelope envelope{};

// Which solver steps a world: the manifold solver once any body has a shape, among the
// definition's bodies or those its respawns bring, or any joint, collision filter or sensor is
// set; the disc solver otherwise. Scenes ask it to know which of the envelope's speed limits
// applies.
inline bool uses_manifold_solver(bool any_shaped_body, bool any_joint_filter_or_sensor = false) {
    return any_shaped_body || any_joint_filter_or_sensor;
}

// The moment of inertia about the centroid of a body of this definition's shape and mass,
// kg m^2 (m r^2 / 2 for a disc).
double inertia_of(const BodyDef& def);

// Bodies [first, first + bodies.size()) are replaced by `bodies` at the first step that starts
// at or after `at`: a generator's set removed and a new one scattered. Contacts of the old
// bodies are forgotten; throws keep acting on the body slots by index.
struct RespawnDef {
    double at = 0.0;               // seconds
    std::size_t first = 0;         // index into WorldDef::bodies
    std::vector<BodyDef> bodies;
};

// A spring that softens a joint: its natural frequency and damping ratio, as the joint's two
// bodies would ring with their masses alone (Box2D's hertz and damping ratio).
struct SpringDef {
    double frequency = 0.0;        // Hz, > 0
    double damping = 0.0;          // damping ratio, >= 0 (1: critically damped)
};

// A joint between two bodies, or between a body and the world (an end with no body is fixed
// where its anchor is at t = 0). Anchors and the axis are given in the world at t = 0, and are
// fixed to each body from then on (docs/physics.md, "Joints").
struct JointDef {
    enum class Kind {
        revolute,    // a pin: the bodies share a point and turn freely about it
        distance,    // a rod (fixed length), a rope (never longer) or a spring
        prismatic,   // a slider: B moves along `axis` fixed in A, without turning against A
        weld,        // glued at their relative pose at t = 0 (or held to it by a spring)
    };
    Kind kind = Kind::revolute;
    std::optional<std::size_t> a, b;   // indices into WorldDef::bodies; none: the world
    Vec2 anchor_a;                 // metres, in the world at t = 0 (revolute, prismatic, weld:
    Vec2 anchor_b;                 // both the one shared point)
    Vec2 axis{1.0, 0.0};           // prismatic: the direction of travel at t = 0 (any length)
    double length = -1.0;          // distance: metres; below 0: the anchors' distance at t = 0
    bool rope = false;             // distance: may be shorter than `length`, never longer
    std::optional<SpringDef> spring;   // distance and weld: soft; absent: rigid
    // Revolute: B's angle less A's, relative to t = 0, radians; prismatic: B's travel along
    // the axis from t = 0, metres. lower <= upper.
    std::optional<std::array<double, 2>> limits;
    // Revolute: relative turning speed (rad/s) up to `max_force` N m of torque; prismatic:
    // sliding speed (m/s) up to `max_force` N.
    struct Motor {
        double speed = 0.0;
        double max_force = 0.0;
    };
    std::optional<Motor> motor;
    bool collide = false;          // whether the two bodies still collide with each other
};

struct WorldDef {
    Vec2 gravity{0.0, -9.81};      // m/s^2
    int rate = 480;                // steps per second; one step() advances 1/rate s
    int substeps = 0;              // solver substeps per step; 0: the fewest that keep a
                                   // substep at or under 1/480 s (docs/physics.md)
    int iterations = 0;            // velocity iterations per substep: more hold a tall pile
                                   // tighter (docs/physics.md); 0: the solver's own, 3 for
                                   // plain discs and 6 with shapes; below 0: 1
    // Islands of bodies at rest fall asleep (stop, and cost nothing) until something reaches
    // them (docs/physics.md, "Sleeping"). Scenes with a shape only, for now.
    bool sleep = true;
    Mixing mixing;                 // how two materials make a contact's
    // Time the stages of every step (World::profile): for benches and for finding where a
    // scene's time goes. It changes nothing the steps compute.
    bool profile = false;
    std::vector<BodyDef> bodies;
    std::vector<WallDef> walls;
    std::vector<ThrowDef> throws;
    std::vector<RespawnDef> respawns;   // in order of `at`
    std::vector<JointDef> joints;
};

struct BodyState {
    Vec2 position;                 // metres
    Vec2 velocity;                 // m/s
    double angle = 0.0;            // radians
    double angular_velocity = 0.0; // rad/s
};

// A joint now: where its two anchors are, and what it did in the last substep.
struct JointState {
    Vec2 anchor_a;                 // metres, in the world (A's anchor; the world's if none)
    Vec2 anchor_b;
    Vec2 force;                    // N on B (its opposite on A), the constraint's reaction
    double torque = 0.0;           // N m on B, about its anchor
};

// A pair that was not touching one step before and touches now: one per pair of bodies,
// whatever the number of points their contact has.
struct ContactEvent {
    // A contact began; or a body began or ended overlapping a sensor (impulse 0).
    enum class Kind { contact, begin, end };
    Kind kind = Kind::contact;
    double t = 0.0;                // seconds, time of the step that found it
    std::size_t a = 0;             // body index
    enum class Other { body, wall };
    Other other_kind = Other::body;
    std::size_t other = 0;         // body index or index into WorldDef::walls
    double impulse = 0.0;          // N*s, total normal impulse applied in that step
};

// Where bodies touch now, for drawing (style.debug): one per point of a contact that pushed in
// the last step (a manifold has one or two; two discs, or a disc and a wall, one).
struct ContactPoint {
    std::size_t a = 0;             // body index
    ContactEvent::Other other_kind = ContactEvent::Other::body;
    std::size_t other = 0;         // body index or index into WorldDef::walls
    Vec2 point;                    // metres, on body a's surface
    Vec2 normal;                   // unit, from a towards the other
    // N along the normal: the resting push of the last substep (an impact's impulse is not in
    // it: a contact of a bounce alone has none).
    double force = 0.0;
};

// A snapshot of quantities the CLI's summary and tests read; O(bodies + contacts) to compute.
struct WorldStats {
    double kinetic_energy = 0.0;    // J, translational + rotational, over non-static bodies
    double potential_energy = 0.0;  // J, -m g.x over non-static bodies (zero at the origin)
    double max_overlap = 0.0;       // metres, deepest overlap between two bodies right now
    double max_overlap_ratio = 0.0; // that overlap over the smaller radius involved
    std::size_t contact_count = 0;  // pairs that exchanged an impulse during the last step
    // Times of impact of a pair of bodies computed during the last step (bodies of any shape):
    // bounded per step, however fast the bodies (docs/physics.md, "Continuous collision").
    std::size_t sweeps = 0;
};

// Where a world's steps spent their time, by stage: seconds of the steady clock summed over
// every step since the world was made, when WorldDef::profile asks for it (zeros otherwise).
// Both solvers' steps are divided into these stages (docs/physics-speed.md says what each
// holds; the manifold solver's bounces count as velocities, though they follow its positions).
struct StepProfile {
    double pairs = 0.0;        // s: the broad phase, the pairs that may touch
    double contacts = 0.0;     // s: each near pair's contact (manifold or gap), islands planned
    double impacts = 0.0;      // s: times of impact, strikes, and the collisions at them
    double velocities = 0.0;   // s: the velocity solve (rows, islands), and the bounces
    double positions = 0.0;    // s: positions moved, overlap pushed out
    double rest = 0.0;         // s: the rest of the step: throws, respawns, events, sleep
    double total() const { return pairs + contacts + impacts + velocities + positions + rest; }
};

// The first body whose state stopped being finite: the scene asked for more than double
// precision can carry (the scene loader's limits keep ordinary scenes far from this).
struct NonFiniteState {
    std::size_t body = 0;          // index into WorldDef::bodies
    double t = 0.0;                // seconds, the end of the step that produced it
};

class World {
public:
    explicit World(const WorldDef& def);
    ~World();
    World(World&&) noexcept;
    World& operator=(World&&) noexcept;
    // A checkpoint: the copy steps on to the same bytes as this world would (contacts, warm
    // starts and caches copied too). Not profiled.
    World(const World& other);
    World& operator=(const World&) = delete;

    void step();                   // advance by exactly 1/rate seconds; nothing once failed
    std::int64_t step_count() const;
    int rate() const;              // steps per second (WorldDef::rate)
    double time() const;           // step_count() / rate(), seconds
    int substeps() const;          // per step: WorldDef::substeps, or the count chosen for 0
    // True when some body has a shape or a joint joins bodies: the manifold solver steps the
    // world (docs/physics.md).
    bool manifold_solver() const;
    // Velocity iterations per substep of the solver in use: WorldDef::iterations, or for 0
    // the solver's own.
    int iterations() const;

    // Same order as WorldDef::discs; valid until the next step() (ask again after it).
    std::span<const BodyState> bodies() const;

    // Same order as WorldDef::joints; valid until the next step().
    std::span<const JointState> joints() const;

    // The points where bodies touch now, in a deterministic order (ContactPoint).
    std::vector<ContactPoint> contact_points() const;
    // Per body, in definition order: whether it is part of a sleeping island (manifold solver).
    std::vector<bool> sleeping() const;

    // How many of WorldDef::respawns have been carried out.
    std::size_t respawns_applied() const;

    // Contacts that began during the steps since the last call, in a deterministic order.
    std::vector<ContactEvent> take_events();

    // Set once any disc's position, velocity, angle or spin is NaN or infinite, after a step
    // or already in the definition; step() does nothing from then on.
    std::optional<NonFiniteState> failure() const;

    WorldStats stats() const;
    double energy() const;         // kinetic + potential, J (see WorldStats)
    StepProfile profile() const;   // zeros unless WorldDef::profile

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace discreel::physics
