#include "disc_stepper.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <optional>
#include <span>

#include "stage_timer.hpp"

namespace discreel::physics::detail {
namespace {

constexpr int projection_iterations = 2;
// The disc solver's velocity iterations when a scene sets none (docs/physics.md).
constexpr int disc_iterations = 3;

// x where mask is all ones, +0 where it is zero.
double masked(double x, std::uint64_t mask) {
    return std::bit_cast<double>(std::bit_cast<std::uint64_t>(x) & mask);
}

}  // namespace

DiscStepper::DiscStepper(const WorldDef& def, int substeps, std::vector<Body>& bodies)
    : gravity_(to_v2(def.gravity)),
      rate_(def.rate),
      substeps_(substeps),
      iterations_(def.iterations == 0 ? disc_iterations : std::max(1, def.iterations)),
      disc_count_(def.bodies.size()),
      features_(features_of(def.walls)) {
    broad_phase_.set_mixing(def.mixing);
    projector_.set_mixing(def.mixing);
    for (const Feature& f : features_) {
        Body b;
        b.restitution = def.walls[f.wall].restitution;
        b.friction = def.walls[f.wall].friction;
        bodies.push_back(b);
    }
}

void DiscStepper::step(std::vector<Body>& bodies, double /*t0*/, double /*t1*/, bool thrown,
                       std::vector<PairTouch>& began) {
    const double dt = 1.0 / rate_;
    if (thrown) ++bodies_version_;
    {
        const StageTimer timer(profile_, &StepProfile::pairs);
        if (broad_phase_.update(bodies, disc_count_, features_, dt, gravity_.norm(), contacts_,
                                thrown ? std::nullopt : std::optional<bool>(list_kept_))) {
            ++contacts_version_;
        }
    }
    const double h = dt / substeps_;
    for (int k = 0; k < substeps_; ++k) substep(bodies, h, k == substeps_ - 1);
    collect_touches(began);
}

void DiscStepper::substep(std::vector<Body>& bodies, double h, bool last) {
    std::optional<StageTimer> listing(std::in_place, profile_, &StepProfile::contacts);
    const double fall = 0.5 * gravity_.norm() * h * h;
    // How far each body can travel in this substep, computed once rather than per contact.
    reach_.resize(bodies.size());
    start_.resize(disc_count_);
    // Hoisted by hand: the stores below could alias the vectors' own pointers for all the
    // compiler knows, so it would reload them for every body and contact.
    Body* const body_at = bodies.data();
    double* const reach_of = reach_.data();
    V2* const start_of = start_.data();
    const std::size_t body_count = bodies.size();
    const std::size_t discs = disc_count_;
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
    Substep s{bodies, disc_count_, features_, contacts_, contacts_version_, bodies_version_,
              active_, reach_, gravity_, h};
    impact_resolver_.begin(s);
    contact_solver_.begin(s);
    active_.clear();
    // A block of contacts at a time, in two passes. The first finds every pair's gap without
    // branching on whether it is near (that is data-dependent, about half the pairs in a pile,
    // and a misprediction exposes the square root's latency), so it takes every pair's square
    // root rather than ruling far ones out with certainly_farther (which never disagrees with
    // the gap); the second hands the near ones to the stages while the block is in cache.
    constexpr std::size_t block = 256;
    std::array<std::uint32_t, block> near_in_block{};
    Contact* const contact_at = contacts_.data();
    const Feature* const feature_at = features_.data();
    const std::size_t contact_count = contacts_.size();
    for (std::size_t first = 0; first < contact_count; first += block) {
        const std::size_t end = std::min(first + block, contact_count);
        std::size_t near_count = 0;
        for (std::size_t i = first; i < end; ++i) {
            Contact& c = contact_at[i];
            const Body& a = body_at[c.a];
            const double reach_sum = reach_of[c.a] + reach_of[c.b];
            // Only the gap is kept: the resting stage takes its normal at the end of the substep.
            c.gap = c.b >= discs
                        ? disc_feature(a.x, a.radius, feature_at[c.b - discs]).gap
                        : disc_disc(a.x, a.radius, body_at[c.b].x, body_at[c.b].radius).gap;
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
        impact_resolver_.screen(s, listed, active_.size());
        contact_solver_.list(s, listed);
        active_.insert(active_.end(), listed.begin(), listed.end());
    }
    contact_solver_.plan_islands(s);
    listing.reset();
    {
        const StageTimer timer(profile_, &StepProfile::impacts);
        impact_resolver_.resolve(s, contact_solver_.islands());
    }
    {
        // The resting stage moves the positions too, by the mean of the substep's velocities.
        const StageTimer timer(profile_, &StepProfile::velocities);
        contact_solver_.solve(s, iterations_);
    }
    const StageTimer timer(profile_, &StepProfile::positions);
    projector_.project(s, projection_iterations);
    // The last substep's runaways are left to end_step's pass over the discs.
    if (!last) projector_.contain_runaways(s, start_, reach_);
}

void DiscStepper::collect_touches(std::vector<PairTouch>& began) {
    contacts_last_step_ = 0;
    for (Contact& c : contacts_) {
        const bool touching = c.step_impulse > 0.0;
        if (touching) ++contacts_last_step_;
        if (touching && !c.touched_before) began.push_back({c.a, c.b, c.step_impulse, true});
        c.touched_before = touching;
        c.step_impulse = 0.0;  // the broad phase adds new contacts with none
    }
}

std::optional<std::size_t> DiscStepper::end_step(std::vector<Body>& bodies, double dt) {
    // One pass over the discs per step, for the last substep's runaways (each disc is handled
    // on its own, and the throws' end of the step only moved held discs, which they leave
    // alone) and two questions. Is the state finite? 0 u is 0 for a finite u and NaN
    // otherwise, so the sum is 0 exactly when all are finite; only a total that is not 0 looks
    // for the first culprit. Does the broad phase's pair list stay valid for the next step?
    // (Asked here rather than in a pass of its own; throws that change a body at the start of
    // the step ask again.) dt = 0: before the first step, with no substep's runaways.
    const auto finite_zero = [](const Body& b) {
        return V2(b.x * 0.0 + b.v * 0.0 + V2(b.angle, b.omega) * 0.0);
    };
    const double g = gravity_.norm();
    const bool runaways = dt > 0.0;
    bool kept = broad_phase_.built() && dt > 0.0;
    V2 all_finite_zero = V2::Zero();
    for (std::size_t i = 0; i < disc_count_; ++i) {
        if (runaways) {
            projector_.contain_runaway(bodies, disc_count_, features_, i, start_[i],
                                               reach_[i]);
        }
        const Body& b = bodies[i];
        all_finite_zero += finite_zero(b);
        if (kept && b.moves()) kept = broad_phase_.keeps(b, i, dt, g);
    }
    list_kept_ = kept;
    if (all_finite_zero.x() + all_finite_zero.y() == 0.0) return std::nullopt;
    for (std::size_t i = 0; i < disc_count_; ++i) {
        const V2 zero = finite_zero(bodies[i]);
        if (zero.x() + zero.y() != 0.0) return i;
    }
    return std::nullopt;
}

void DiscStepper::forget(std::vector<Body>& /*bodies*/, std::size_t first, std::size_t last) {
    // The replacements may differ in radius and mass (the stages' caches follow the versions)
    // and stand anywhere: the broad phase lists their pairs afresh, with no warm start.
    broad_phase_.forget(first, last, contacts_);
    impact_resolver_.bodies_replaced();
    ++contacts_version_;
    ++bodies_version_;
}

void DiscStepper::add_stats(const std::vector<Body>& bodies, std::size_t /*body_count*/,
                            WorldStats& stats) const {
    for (const Contact& c : contacts_) {
        const Body& a = bodies[c.a];
        const Body& b = bodies[c.b];
        const bool wall = c.b >= disc_count_;
        const Proximity p = wall ? disc_feature(a.x, a.radius, features_[c.b - disc_count_])
                                 : disc_disc(a.x, a.radius, b.x, b.radius);
        if (-p.gap > stats.max_overlap) {
            stats.max_overlap = -p.gap;
            stats.max_overlap_ratio = -p.gap / (wall ? a.radius : std::min(a.radius, b.radius));
        }
    }
    stats.contact_count = contacts_last_step_;
}

void DiscStepper::contact_points(const std::vector<Body>& bodies, std::size_t /*body_count*/,
                                 std::vector<ContactPoint>& out) const {
    for (const Contact& c : contacts_) {
        if (!c.touched_before) continue;   // near, but it did not push in the last step
        const Body& a = bodies[c.a];
        const bool wall = c.b >= disc_count_;
        const Proximity p = wall ? disc_feature(a.x, a.radius, features_[c.b - disc_count_])
                                 : disc_disc(a.x, a.radius, bodies[c.b].x, bodies[c.b].radius);
        const V2 n = -p.normal;   // Proximity's points from the other towards a
        const V2 at = a.x + n * a.radius;
        out.push_back({.a = c.a,
                       .other_kind = ContactEvent::Other::body,
                       .other = c.b,
                       .point = {at.x(), at.y()},
                       .normal = {n.x(), n.y()},
                       .force = c.normal_impulse});
    }
}

}  // namespace discreel::physics::detail
