// The fixed-rate world: the bodies, throws, respawns, events and shared measures, stepped by
// the disc solver (disc_stepper.hpp) or, once any body has a shape or a joint joins bodies,
// the manifold solver (shape_stepper.hpp).
#include <algorithm>
#include <cmath>
#include <memory>
#include <span>
#include <utility>

#include "disc_stepper.hpp"
#include "discreel/physics.hpp"
#include "shape_stepper.hpp"
#include "stage_timer.hpp"
#include "stepper.hpp"
#include "kinematics.hpp"
#include "throws.hpp"

namespace discreel::physics {

using detail::Body;
using detail::Motion;
using detail::PairTouch;

namespace {

// Substeps are sized so that one lasts at most this long (documented in docs/physics.md).
constexpr double longest_substep = 1.0 / 480.0;  // s

bool any_shape(const WorldDef& def) {
    const auto shaped = [](const BodyDef& d) { return d.shape.has_value(); };
    return std::any_of(def.bodies.begin(), def.bodies.end(), shaped) ||
           std::any_of(def.respawns.begin(), def.respawns.end(), [&](const RespawnDef& r) {
               return std::any_of(r.bodies.begin(), r.bodies.end(), shaped);
           });
}

// Joints, filters and sensors are the manifold solver's.
bool any_joint_filter_or_sensor(const WorldDef& def) {
    const auto set = [](const BodyDef& d) {
        return d.sensor || filters(d.category, d.collides, false);
    };
    const auto wall_set = [](const WallDef& w) { return filters(w.category, w.collides, true); };
    return !def.joints.empty() || std::any_of(def.bodies.begin(), def.bodies.end(), set) ||
           std::any_of(def.walls.begin(), def.walls.end(), wall_set) ||
           std::any_of(def.respawns.begin(), def.respawns.end(), [&](const RespawnDef& r) {
               return std::any_of(r.bodies.begin(), r.bodies.end(), set);
           });
}

}  // namespace

struct World::Impl {
    explicit Impl(const WorldDef& def)
        : rate(def.rate),
          substeps(def.substeps > 0 ? def.substeps
                                    : std::max(1, static_cast<int>(std::ceil(
                                                      1.0 / (longest_substep * def.rate))))),
          gravity(def.gravity),
          body_count(def.bodies.size()),
          manifold(uses_manifold_solver(any_shape(def), any_joint_filter_or_sensor(def))),
          throws(def.throws),
          kinematics(def.bodies),
          respawns(def.respawns),
          profiled(def.profile) {
        for (const BodyDef& d : def.bodies) bodies.push_back(detail::make_body(d));
        if (manifold) {
            stepper = std::make_unique<detail::ShapeStepper>(def, substeps, bodies);
        } else {
            stepper = std::make_unique<detail::DiscStepper>(def, substeps, bodies);
        }
        if (def.profile) stepper->set_profile(&profile);
        throws.start(bodies);
        kinematics.start(bodies);
        states.resize(body_count);
        if (const auto i = stepper->end_step(bodies, 0.0)) failure = NonFiniteState{*i, 0.0};
    }

    // A copy that steps on exactly as `other` would; not profiled.
    Impl(const Impl& other)
        : rate(other.rate), substeps(other.substeps), gravity(other.gravity),
          body_count(other.body_count), manifold(other.manifold), bodies(other.bodies),
          throws(other.throws), kinematics(other.kinematics), respawns(other.respawns),
          respawns_applied(other.respawns_applied), stepper(other.stepper->clone()),
          events(other.events), states(other.states), published_steps(other.published_steps),
          steps(other.steps), failure(other.failure), profiled(false) {}
    Impl& operator=(const Impl&) = delete;
    Impl(Impl&&) = delete;
    Impl& operator=(Impl&&) = delete;
    ~Impl() = default;

    void step();
    void respawn(double t0);
    void add_events(double t);

    int rate;
    int substeps;
    Vec2 gravity;
    std::size_t body_count;
    bool manifold;
    // The definition's bodies, then the stepper's fixed bodies for the walls.
    std::vector<Body> bodies;
    detail::Throws throws;
    detail::Kinematics kinematics;
    std::vector<RespawnDef> respawns;
    std::size_t respawns_applied = 0;
    std::unique_ptr<detail::Stepper> stepper;
    std::vector<PairTouch> began;   // scratch of step()
    std::vector<ContactEvent> events;
    // Filled from the bodies when asked for, not every step (a renderer asks once per frame).
    mutable std::vector<BodyState> states;
    mutable std::int64_t published_steps = -1;  // the step count `states` is for
    mutable std::vector<JointState> joint_states;
    std::int64_t steps = 0;
    std::optional<NonFiniteState> failure;
    bool profiled;
    // The stages' times (the stepper adds them) and, in `rest` until profile() takes them out,
    // the whole steps'.
    StepProfile profile;
};

void World::Impl::step() {
    // A NaN would reach the broad phase's grid, where converting it to a cell is undefined.
    if (failure) return;
    const detail::StageTimer timer(profiled ? &profile : nullptr, &StepProfile::rest);
    const double t0 = static_cast<double>(steps) / rate;
    const double t1 = static_cast<double>(steps + 1) / rate;
    respawn(t0);
    const bool thrown = throws.begin_step(t0, t1, bodies);
    const bool steered = kinematics.begin_step(t0, t1, bodies);
    began.clear();
    stepper->step(bodies, t0, t1, thrown || steered, began);
    throws.end_step(t1, bodies);
    kinematics.end_step(t1, bodies);
    ++steps;
    add_events(t1);
    if (const auto i = stepper->end_step(bodies, 1.0 / rate)) failure = NonFiniteState{*i, t1};
}

void World::Impl::respawn(double t0) {
    while (respawns_applied < respawns.size() && respawns[respawns_applied].at <= t0) {
        const RespawnDef& r = respawns[respawns_applied++];
        const std::size_t last = std::min(body_count, r.first + r.bodies.size());
        stepper->forget(bodies, r.first, last);
        for (std::size_t i = r.first; i < last; ++i) {
            const BodyDef& def = r.bodies[i - r.first];
            Body fresh = detail::make_body(def);
            // A held body stays held: its throw still owns it.
            if (bodies[i].motion == Motion::held) {
                fresh.x = bodies[i].x;
                fresh.v = bodies[i].v;
                fresh.motion = Motion::held;
                fresh.inv_mass = 0;
                fresh.inv_inertia = 0;
            }
            bodies[i] = fresh;
            stepper->replaced(i, def);
        }
    }
}

void World::Impl::add_events(double t) {
    for (const PairTouch& touch : began) {
        ContactEvent e;
        e.t = t;
        e.a = touch.a;
        if (touch.b >= body_count) {
            e.other_kind = ContactEvent::Other::wall;
            e.other = stepper->wall_of(touch.b - body_count);
        } else {
            e.other_kind = ContactEvent::Other::body;
            e.other = touch.b;
        }
        e.impulse = touch.impulse;
        e.kind = touch.kind == PairTouch::Kind::begin ? ContactEvent::Kind::begin
                 : touch.kind == PairTouch::Kind::end ? ContactEvent::Kind::end
                                                      : ContactEvent::Kind::contact;
        events.push_back(e);
    }
}

World::World(const WorldDef& def) : impl_(std::make_unique<Impl>(def)) {}
World::~World() = default;
World::World(World&&) noexcept = default;
World::World(const World& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
World& World::operator=(World&&) noexcept = default;

void World::step() { impl_->step(); }
std::int64_t World::step_count() const { return impl_->steps; }
int World::rate() const { return impl_->rate; }
double World::time() const { return static_cast<double>(impl_->steps) / impl_->rate; }
int World::substeps() const { return impl_->substeps; }
bool World::manifold_solver() const { return impl_->manifold; }
int World::iterations() const { return impl_->stepper->iterations(); }
std::span<const JointState> World::joints() const {
    impl_->stepper->joint_states(impl_->bodies, impl_->joint_states);
    return impl_->joint_states;
}
std::size_t World::respawns_applied() const { return impl_->respawns_applied; }

std::vector<ContactPoint> World::contact_points() const {
    const Impl& w = *impl_;
    std::vector<ContactPoint> points;
    w.stepper->contact_points(w.bodies, w.body_count, points);
    // The steppers give the last substep's resting impulses.
    const double seconds = 1.0 / (static_cast<double>(w.rate) * w.substeps);
    for (ContactPoint& p : points) {
        p.force /= seconds;
        if (p.other < w.body_count) continue;
        p.other_kind = ContactEvent::Other::wall;
        p.other = w.stepper->wall_of(p.other - w.body_count);
    }
    return points;
}

std::vector<bool> World::sleeping() const {
    const Impl& w = *impl_;
    std::vector<bool> asleep(w.body_count);
    for (std::size_t i = 0; i < w.body_count; ++i) asleep[i] = w.bodies[i].asleep;
    return asleep;
}
std::vector<ContactEvent> World::take_events() { return std::exchange(impl_->events, {}); }
std::optional<NonFiniteState> World::failure() const { return impl_->failure; }

std::span<const BodyState> World::bodies() const {
    const Impl& w = *impl_;
    if (w.published_steps != w.steps) {
        w.published_steps = w.steps;
        for (std::size_t i = 0; i < w.body_count; ++i) w.states[i] = detail::state_of(w.bodies[i]);
    }
    return w.states;
}

WorldStats World::stats() const {
    const Impl& w = *impl_;
    WorldStats s;
    detail::add_energy(std::span(w.bodies).first(w.body_count),
                       detail::to_v2(w.gravity), s);
    w.stepper->add_stats(w.bodies, w.body_count, s);
    return s;
}

StepProfile World::profile() const {
    // `rest` holds the whole steps' time until here: the stages' own are taken out of it.
    StepProfile p = impl_->profile;
    p.rest -= p.pairs + p.contacts + p.impacts + p.velocities + p.positions;
    return p;
}

double World::energy() const {
    const WorldStats s = stats();
    return s.kinetic_energy + s.potential_energy;
}

}  // namespace discreel::physics
