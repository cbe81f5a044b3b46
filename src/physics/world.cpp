// The fixed-rate world: each step runs the broad phase once, then `substeps` substeps of
// impacts (impacts.cpp), resting contact (contact_solver.cpp) and position projection.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <span>
#include <utility>

#include "broad_phase.hpp"
#include "contact.hpp"
#include "discreel/physics.hpp"
#include "geometry.hpp"
#include "shape_world.hpp"
#include "substep.hpp"
#include "throws.hpp"

namespace discreel::physics {

using detail::Body;
using detail::Contact;
using detail::V2;

namespace {

// Substeps are sized so that one lasts at most this long (documented in docs/physics.md).
constexpr double longest_substep = 1.0 / 480.0;  // s
constexpr int projection_iterations = 2;
// The disc solver's velocity iterations when a scene sets none (docs/physics.md).
constexpr int disc_iterations = 3;

V2 to_v2(const Vec2& p) { return V2(p.x, p.y); }

// x where mask is all ones, +0 where it is zero.
double masked(double x, std::uint64_t mask) {
    return std::bit_cast<double>(std::bit_cast<std::uint64_t>(x) & mask);
}

}  // namespace

struct World::Impl {
    explicit Impl(const WorldDef& def)
        : rate(def.rate),
          gravity(to_v2(def.gravity)),
          disc_count(def.bodies.size()),
          features(detail::features_of(def.walls)),
          throws(def.throws) {
        iterations = def.iterations == 0 ? disc_iterations : std::max(1, def.iterations);
        substeps = def.substeps > 0
                       ? def.substeps
                       : std::max(1, static_cast<int>(std::ceil(1.0 / (longest_substep * rate))));
        if (detail::ShapeWorld::wanted(def)) {
            shapes = std::make_unique<detail::ShapeWorld>(def, substeps);
            iterations = shapes->iterations();
            if (const auto i = shapes->non_finite()) failure = NonFiniteState{*i, 0.0};
            return;
        }
        for (const BodyDef& d : def.bodies) bodies.push_back(detail::make_body(d));
        for (const detail::Feature& f : features) {
            Body b;
            b.restitution = def.walls[f.wall].restitution;
            b.friction = def.walls[f.wall].friction;
            bodies.push_back(b);
        }
        throws.start(bodies);
        states.resize(disc_count);
        check_finite();
    }

    void step();
    void substep(double h, bool last);
    void collect_events(double t);
    void check_finite() { end_step(0.0, false); }
    // runaways: the last substep left its runaway discs (PositionProjector::contain_runaways)
    // to this pass.
    void end_step(double dt, bool runaways);
    std::span<const BodyState> publish() const;

    int rate;
    int substeps = 1;
    int iterations = 1;
    V2 gravity;
    std::size_t disc_count;
    std::vector<detail::Feature> features;
    std::vector<Body> bodies;
    std::vector<Contact> contacts;
    std::uint64_t contacts_version = 0;  // counts the broad phase's rebuilds
    std::uint64_t bodies_version = 0;    // counts the steps whose throws changed a body
    std::vector<std::uint32_t> active;
    std::vector<double> reach;  // metres per body, scratch of substep()
    std::vector<V2> start;      // disc centres at the start of the substep, scratch
    detail::BroadPhase broad_phase;
    detail::ImpactResolver impact_resolver;
    detail::ContactSolver contact_solver;
    detail::PositionProjector projector;
    detail::Throws throws;
    // Filled from the bodies when asked for, not every step (a renderer asks once per frame).
    mutable std::vector<BodyState> states;
    mutable std::int64_t published_steps = -1;  // the step count `states` is for
    std::vector<ContactEvent> events;
    std::int64_t steps = 0;
    bool list_kept = false;  // BroadPhase::keeps() held for every moving disc after the last step
    std::size_t contacts_last_step = 0;
    std::optional<NonFiniteState> failure;
    std::unique_ptr<detail::ShapeWorld> shapes;   // set when any body has a shape
};

void World::Impl::step() {
    // A NaN would reach the broad phase's grid, where converting it to a cell is undefined.
    if (failure) return;
    const double t0 = static_cast<double>(steps) / rate;
    const double t1 = static_cast<double>(steps + 1) / rate;
    const double dt = 1.0 / rate;
    if (shapes) {
        shapes->step(t0, t1);
        ++steps;
        std::vector<ContactEvent> fresh = shapes->take_events();
        events.insert(events.end(), fresh.begin(), fresh.end());
        if (const auto i = shapes->non_finite()) failure = NonFiniteState{*i, t1};
        return;
    }
    const bool thrown = throws.begin_step(t0, t1, bodies);
    if (thrown) ++bodies_version;
    if (broad_phase.update(bodies, disc_count, features, dt, gravity.norm(), contacts,
                           thrown ? std::nullopt : std::optional<bool>(list_kept))) {
        ++contacts_version;
    }
    const double h = dt / substeps;
    for (int k = 0; k < substeps; ++k) substep(h, k == substeps - 1);
    throws.end_step(t1, bodies);
    ++steps;
    collect_events(t1);
    end_step(dt, true);
}

void World::Impl::substep(double h, bool last) {
    const double fall = 0.5 * gravity.norm() * h * h;
    // How far each body can travel in this substep, computed once rather than per contact.
    reach.resize(bodies.size());
    start.resize(disc_count);
    // Hoisted by hand: the stores below could alias the vectors' own pointers for all the
    // compiler knows, so it would reload them for every body and contact.
    Body* const body_at = bodies.data();
    double* const reach_of = reach.data();
    V2* const start_of = start.data();
    const std::size_t body_count = bodies.size();
    const std::size_t discs = disc_count;
    const auto begin_substep = [&](std::size_t i) {
        Body& b = body_at[i];
        reach_of[i] = b.v.norm() * h + (b.falls() ? fall : 0.0);
        b.shift = V2::Zero();
        b.turn = 0.0;
        b.t_last = 0.0;
        b.strikes = 0;
    };
    for (std::size_t i = 0; i < discs; ++i) {
        begin_substep(i);
        start_of[i] = body_at[i].x;
    }
    for (std::size_t i = discs; i < body_count; ++i) begin_substep(i);
    detail::Substep s{bodies, disc_count, features, contacts, contacts_version, bodies_version,
                      active, reach, gravity, h};
    impact_resolver.begin(s);
    contact_solver.begin(s);
    active.clear();
    // A block of contacts at a time, in two passes. The first finds every pair's gap without
    // branching on whether it is near (that is data-dependent, about half the pairs in a pile,
    // and a misprediction exposes the square root's latency), so it takes every pair's square
    // root rather than ruling far ones out with certainly_farther (which never disagrees with
    // the gap); the second hands the near ones to the stages while the block is in cache.
    constexpr std::size_t block = 256;
    std::array<std::uint32_t, block> near_in_block{};
    Contact* const contact_at = contacts.data();
    const detail::Feature* const feature_at = features.data();
    const std::size_t contact_count = contacts.size();
    for (std::size_t first = 0; first < contact_count; first += block) {
        const std::size_t end = std::min(first + block, contact_count);
        std::size_t near_count = 0;
        for (std::size_t i = first; i < end; ++i) {
            Contact& c = contact_at[i];
            const Body& a = body_at[c.a];
            const double reach_sum = reach_of[c.a] + reach_of[c.b];
            // Only the gap is kept: the resting stage takes its normal at the end of the substep.
            c.gap = c.b >= discs
                        ? detail::disc_feature(a.x, a.radius, feature_at[c.b - discs]).gap
                        : detail::disc_disc(a.x, a.radius, body_at[c.b].x, body_at[c.b].radius).gap;
            const bool near = c.gap <= reach_sum;
            // Apart for good this substep: nothing to warm-start from next time. Masked, as a
            // select here turns back into the branch.
            const std::uint64_t kept = std::uint64_t{0} - static_cast<std::uint64_t>(near);
            c.normal_impulse = masked(c.normal_impulse, kept);
            c.tangent_impulse = masked(c.tangent_impulse, kept);
            near_in_block[near_count] = static_cast<std::uint32_t>(i);
            near_count += static_cast<std::size_t>(near);
        }
        const std::span<const std::uint32_t> listed(near_in_block.data(), near_count);
        impact_resolver.screen(s, listed, active.size());
        contact_solver.list(s, listed);
        active.insert(active.end(), listed.begin(), listed.end());
    }
    contact_solver.plan_islands(s);
    impact_resolver.resolve(s, contact_solver.islands());
    contact_solver.solve(s, iterations);
    projector.project(s, projection_iterations);
    // The last substep's runaways are left to end_step's pass over the discs.
    if (!last) detail::PositionProjector::contain_runaways(s, start, reach);
}

void World::Impl::collect_events(double t) {
    contacts_last_step = 0;
    for (Contact& c : contacts) {
        const bool touching = c.step_impulse > 0.0;
        if (touching) ++contacts_last_step;
        if (touching && !c.touched_before) {
            ContactEvent e;
            e.t = t;
            e.a = c.a;
            if (c.b >= disc_count) {
                e.other_kind = ContactEvent::Other::wall;
                e.other = features[c.b - disc_count].wall;
            } else {
                e.other_kind = ContactEvent::Other::body;
                e.other = c.b;
            }
            e.impulse = c.step_impulse;
            events.push_back(e);
        }
        c.touched_before = touching;
        c.step_impulse = 0.0;  // the broad phase adds new contacts with none
    }
}

void World::Impl::end_step(double dt, bool runaways) {
    // One pass over the discs per step, for the last substep's runaways (each disc is handled
    // on its own, and throws.end_step only moved held discs, which they leave alone) and two
    // questions. Is the state finite? 0 u is 0 for a finite u and NaN otherwise, so the sum
    // is 0 exactly when all are finite; only a total that is not 0 looks for the first culprit.
    // Does the broad phase's pair list stay valid for the next step? (Asked here rather than
    // in a pass of its own; throws that change a body at the start of the step ask again.)
    const auto finite_zero = [](const Body& b) {
        return V2(b.x * 0.0 + b.v * 0.0 + V2(b.angle, b.omega) * 0.0);
    };
    const double g = gravity.norm();
    bool kept = broad_phase.built() && dt > 0.0;
    V2 all_finite_zero = V2::Zero();
    for (std::size_t i = 0; i < disc_count; ++i) {
        if (runaways) {
            detail::PositionProjector::contain_runaway(bodies, disc_count, features, i, start[i],
                                                       reach[i]);
        }
        const Body& b = bodies[i];
        all_finite_zero += finite_zero(b);
        if (kept && b.moves()) kept = broad_phase.keeps(b, i, dt, g);
    }
    list_kept = kept;
    if (failure || all_finite_zero.x() + all_finite_zero.y() == 0.0) return;
    for (std::size_t i = 0; i < disc_count; ++i) {
        const V2 zero = finite_zero(bodies[i]);
        if (zero.x() + zero.y() != 0.0) {
            failure = NonFiniteState{i, static_cast<double>(steps) / rate};
            return;
        }
    }
}

std::span<const BodyState> World::Impl::publish() const {
    if (shapes) return shapes->states();
    if (published_steps != steps) {
        published_steps = steps;
        for (std::size_t i = 0; i < disc_count; ++i) states[i] = detail::state_of(bodies[i]);
    }
    return states;
}

World::World(const WorldDef& def) : impl_(std::make_unique<Impl>(def)) {}
World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

void World::step() { impl_->step(); }
std::int64_t World::step_count() const { return impl_->steps; }
int World::rate() const { return impl_->rate; }
double World::time() const { return static_cast<double>(impl_->steps) / impl_->rate; }
int World::substeps() const { return impl_->substeps; }
bool World::manifold_solver() const { return impl_->shapes != nullptr; }
int World::iterations() const { return impl_->iterations; }
std::span<const BodyState> World::bodies() const { return impl_->publish(); }
std::size_t World::respawns_applied() const {
    return impl_->shapes ? impl_->shapes->respawns_applied() : 0;
}
std::vector<ContactEvent> World::take_events() { return std::exchange(impl_->events, {}); }
std::optional<NonFiniteState> World::failure() const { return impl_->failure; }

WorldStats World::stats() const {
    const Impl& w = *impl_;
    if (w.shapes) return w.shapes->stats(w.gravity);
    WorldStats s;
    detail::add_energy(std::span(w.bodies).first(w.disc_count), w.gravity, s);
    for (const Contact& c : w.contacts) {
        const Body& a = w.bodies[c.a];
        const Body& b = w.bodies[c.b];
        const bool wall = c.b >= w.disc_count;
        const detail::Proximity p =
            wall ? detail::disc_feature(a.x, a.radius, w.features[c.b - w.disc_count])
                 : detail::disc_disc(a.x, a.radius, b.x, b.radius);
        if (-p.gap > s.max_overlap) {
            s.max_overlap = -p.gap;
            s.max_overlap_ratio = -p.gap / (wall ? a.radius : std::min(a.radius, b.radius));
        }
    }
    s.contact_count = w.contacts_last_step;
    return s;
}

double World::energy() const {
    const WorldStats s = stats();
    return s.kinetic_energy + s.potential_energy;
}

}  // namespace discreel::physics
