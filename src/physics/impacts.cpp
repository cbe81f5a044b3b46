// Continuous collision and restitution. Each substep, a pair that is approaching and meets
// within the substep (by the swept test in geometry.cpp, so a fast disc never passes through)
// gets the impulse j = -(1 + e) v_n / (1/m_a + 1/m_b) from its approach speed at the time of
// impact, with Coulomb friction. The bodies keep their pre-impact velocity up to that time,
// which Body::shift accounts for, so an isolated bounce is exact: no energy is gained or lost
// to the time discretisation. Impacts happen one at a time in time order (ties by pair), each
// re-predicting only its two bodies' pairs, which lets a hit travel down a row of touching discs
// (Newton's cradle) instead of being shared out, and never lets a body meet a later impact
// before an earlier one.
#include <algorithm>
#include <cmath>
#include <optional>

#include "impacts.hpp"

namespace discreel::physics::detail {
namespace {

// Predictions per substep, per disc (at least 64 discs' worth): a few discs ping-ponging fast
// (a light disc between a heavy one and a wall needs about pi sqrt(M/m) bounces; a crowd at 10
// radii per step meets several discs and walls per step, each impact re-predicting its bodies'
// pairs) get every event, while a heap colliding everywhere at once, or a light disc squeezed
// between heavy ones that would bounce forever, costs at most about 20 us per disc and
// substep. Whatever still approaches once they are spent is handled by the resting stage
// (bounce of at most e), as a pile's squeezes are. docs/physics.md ("Limits") has what they
// cover.
constexpr std::size_t per_disc = 512;

// Approach speeds below this are rounding noise, not impacts. Approaches slower than what
// gravity adds in one substep are resting contact too: the resting stage handles them, still
// with a bounce of up to e times the approach speed, only without the time-of-impact timing.
// Left here, a pile would cost thousands of micro-impacts per substep.
constexpr double min_approach_speed = 1e-9;  // m/s

// Such a pair is timed only if its bounce would be worth it: leaving fast enough (e times its
// approach speed) to rise `visible_bounce` radii against gravity ((e v)^2 / 2|g| = f r), or
// approaching fast enough to close `closing_step` radii within the substep. A landing heap has
// hundreds of slower squeezes per substep, each fanning out over its neighbours; the resting
// stage stops them instead and lets them leave at most e times as fast, untimed (Box2D times
// nothing and gives no bounce at all under 1 m/s). The bounce is judged by the speed the pair
// leaves with, not the one it approaches with, so every elastic row stays timed while a heap of
// low restitution times only the squeezes that would bounce visibly. The closing bound keeps a
// fast squeeze of low-restitution discs in a jam timed, which the resting stage's few iterations
// would not stop before it sank in visibly. A row of touching discs struck at speed (Newton's
// cradle) and every pair that starts apart keep the exact timed impact; without gravity every
// touching approach with e > 0 is timed (an elastic gas). What each bound costs and saves:
// docs/tried.md.
constexpr double visible_bounce = 0.05;
constexpr double closing_step = 0.02;

Trajectory trajectory(const Substep& s, const Body& b) {
    return Trajectory{b.x + b.shift, b.v, s.gravity_on(b)};
}

// The impact of contact c in this substep, if its pair approaches faster than `slow` then,
// for a pair that surely_no_impact did not rule out. Kept out of line so that the cheap tests
// before it are inlined into the callers (a settled pile never gets here).
[[gnu::noinline]] std::optional<Impact> swept_impact(const Substep& s, const Contact& c,
                                                     double slow) {
    const Body& a = s.bodies[c.a];
    const Body& b = s.bodies[c.b];
    const Feature* f = s.feature_of(c);
    const double t_min = std::max(a.t_last, b.t_last);
    const Trajectory ta = trajectory(s, a);
    std::optional<Impact> hit =   // not const: returned, so moved
        f ? impact_disc_feature(ta, a.radius, *f, t_min, s.h)
          : impact_disc_disc(ta, a.radius, trajectory(s, b), b.radius, t_min, s.h);
    if (!hit) return std::nullopt;
    const V2 va = a.v + s.gravity_on(a) * hit->t;
    const V2 vb = b.v + s.gravity_on(b) * hit->t;
    if (hit->normal.dot(va - vb) >= -slow) return std::nullopt;
    return hit;
}

}  // namespace

inline std::optional<Impact> ImpactResolver::find_impact(const Substep& s, const Contact& c,
                                                         double slow) const {
    const double slowest = slowest_impact(s, c, slow);
    if (surely_no_impact(s, c, slowest)) return std::nullopt;
    return swept_impact(s, c, slowest);
}

void ImpactResolver::list_contacts_of_bodies(const Substep& s) {
    listed_version_ = s.contacts_version;
    contacts_of_start_.assign(s.bodies.size() + 1, 0);
    for (const Contact& c : s.contacts) {
        ++contacts_of_start_[c.a + 1];
        ++contacts_of_start_[c.b + 1];
    }
    for (std::size_t i = 0; i < s.bodies.size(); ++i) {
        contacts_of_start_[i + 1] += contacts_of_start_[i];
    }
    contacts_of_.resize(2 * s.contacts.size());
    fill_.assign(contacts_of_start_.begin(), contacts_of_start_.end() - 1);
    for (std::size_t i = 0; i < s.contacts.size(); ++i) {
        const Contact& c = s.contacts[i];
        contacts_of_[fill_[c.a]++] = static_cast<std::uint32_t>(i);
        contacts_of_[fill_[c.b]++] = static_cast<std::uint32_t>(i);
    }
    // Entries left from the previous list carry an older listing_, so they read as stale.
    position_.resize(s.contacts.size());
}

void ImpactResolver::begin(const Substep& s) {
    if (s.contacts_version != listed_version_) list_contacts_of_bodies(s);
    ++listing_;
    gravity_step_ = s.gravity.norm() * s.h;
    slow_ = std::max(min_approach_speed, gravity_step_);
    screened_.clear();
    // Per body, because the threshold grows with the radius: a pair's is its smaller disc's.
    // Gravity and the substep's length never change within a world, and radii only when a
    // respawn replaces discs (bodies_replaced).
    if (reach_.size() != s.bodies.size()) {
        reach_.assign(s.bodies.size(), 0.0);
        reach_listing_.assign(s.bodies.size(), never);
    }
    if (settle_.size() != s.disc_count || settle_h_ != s.h) {
        settle_h_ = s.h;
        settle_.resize(s.disc_count);
        for (std::size_t i = 0; i < s.disc_count; ++i) {
            const double r = s.bodies[i].radius;
            settle_[i] = Settle{std::sqrt(2.0 * visible_bounce * s.gravity.norm() * r),
                                closing_step * r / s.h};
        }
    }
}

bool ImpactResolver::apply(Substep& s, const Event& e) {
    Contact& c = s.contacts[s.active[e.k]];
    Body& a = s.bodies[c.a];
    Body& b = s.bodies[c.b];
    if (a.strikes != e.strikes_a || b.strikes != e.strikes_b) return false;
    const Impact& hit = e.hit;
    const V2& n = hit.normal;
    const V2 va = a.v + s.gravity_on(a) * hit.t;
    const V2 vb = b.v + s.gravity_on(b) * hit.t;
    const double vn = n.dot(va - vb);
    const double jn = -(1.0 + c.restitution) * vn / normal_mass_inverse(a, b);
    const double vt = perp(n).dot(va - vb) - a.radius * a.omega - b.radius * b.omega;
    const double limit = c.friction * jn;
    const double jt = std::clamp(-vt / tangent_mass_inverse(a, b), -limit, limit);

    const V2 va0 = a.v, vb0 = b.v;
    const double wa0 = a.omega, wb0 = b.omega;
    apply_impulse(a, b, n, n * jn + perp(n) * jt);
    a.shift -= (a.v - va0) * hit.t;
    b.shift -= (b.v - vb0) * hit.t;
    a.turn -= (a.omega - wa0) * hit.t;
    b.turn -= (b.omega - wb0) * hit.t;
    // Walls, pegs and held discs keep their motion, so they carry no impact history.
    for (Body* body : {&a, &b}) {
        if (body->inv_mass == 0.0) continue;
        body->t_last = std::max(body->t_last, hit.t);
        ++body->strikes;
    }
    c.step_impulse += jn;
    return true;
}

void ImpactResolver::widen_reach(Substep& s, std::uint32_t i, double t) {
    const auto reach_of = [&](std::uint32_t j) {
        return reach_listing_[j] == listing_ ? reach_[j] : s.reach[j];
    };
    const Body& body = s.bodies[i];
    // Travelled by time t, then at most its speed for the rest of the substep; gravity's part
    // of both is within the fall over the whole substep.
    const double fall = body.falls() ? 0.5 * gravity_step_ * s.h : 0.0;
    const double widest = (body.shift + body.v * t).norm() +
                          (body.v + s.gravity_on(body) * t).norm() * (s.h - t) + fall;
    const double before = reach_of(i);
    if (widest <= before) return;
    reach_[i] = widest;
    reach_listing_[i] = listing_;
    for (std::uint32_t e = contacts_of_start_[i]; e < contacts_of_start_[i + 1]; ++e) {
        const std::uint32_t index = contacts_of_[e];
        std::uint32_t k;
        if (active_position(index, k)) continue;
        const Contact& c = s.contacts[index];
        if (s.bodies[c.a].inv_mass + s.bodies[c.b].inv_mass == 0.0) continue;
        if (c.gap > reach_of(c.a) + reach_of(c.b)) continue;
        // Not in the resting stage's rows (they were built when the substep began); the
        // projection stage sees it through s.active.
        position_[index] = (listing_ << 32) | static_cast<std::uint64_t>(s.active.size());
        s.active.push_back(index);
        if (predicted_.size() < s.active.size()) predicted_.resize(s.active.size(), never);
    }
}

void ImpactResolver::predict_pairs_of(const Substep& s, const DiscIslands& islands,
                                      std::uint32_t i, double slow, std::size_t& spent) {
    for (std::uint32_t e = contacts_of_start_[i]; e < contacts_of_start_[i + 1]; ++e) {
        std::uint32_t k;
        if (!active_position(contacts_of_[e], k) || predicted_[k] == events_done_) continue;
        if (islands.in_island(contacts_of_[e])) continue;
        predicted_[k] = events_done_;
        ++spent;
        if (const std::optional<Impact> hit = find_impact(s, s.contacts[s.active[k]], slow)) {
            push(s, k, *hit);
        }
    }
}

void ImpactResolver::resolve(Substep& s, const DiscIslands& islands) {
    const double slow = slow_;
    const std::size_t budget = per_disc * std::max<std::size_t>(s.disc_count, 64);
    // Predictions, counted against the budget; the first ones cover every active pair.
    std::size_t spent = s.active.size();
    events_.clear();
    // No body has changed since screen() passed these pairs.
    for (const std::uint32_t k : screened_) {
        if (islands.in_island(s.active[k])) continue;
        const Contact& c = s.contacts[s.active[k]];
        if (const std::optional<Impact> hit = swept_impact(s, c, slowest_impact(s, c, slow))) {
            events_.push_back(Event{*hit, k, 0, 0});
        }
    }
    std::make_heap(events_.begin(), events_.end(), later);
    if (predicted_.size() < s.active.size()) predicted_.resize(s.active.size(), never);
    // Discs a direct island's collision sped up at the start of the substep: as after an
    // impact here, their reach grows and their pairs outside the island are predicted.
    if (!islands.collided().empty()) {
        ++events_done_;
        for (const std::uint32_t i : islands.collided()) widen_reach(s, i, 0.0);
        for (const std::uint32_t i : islands.collided()) {
            predict_pairs_of(s, islands, i, slow, spent);
        }
    }
    // A settled pile has no impacts at all.
    if (events_.empty()) return;
    while (!events_.empty()) {
        std::pop_heap(events_.begin(), events_.end(), later);
        const Event e = events_.back();
        events_.pop_back();
        if (!apply(s, e)) continue;
        // Once the budget is spent, the pairs still approaching are left to the resting stage.
        if (spent >= budget) break;
        ++events_done_;
        const Contact& c = s.contacts[s.active[e.k]];
        for (const std::uint32_t i : {c.a, c.b}) {
            if (s.bodies[i].inv_mass != 0.0) widen_reach(s, i, e.hit.t);
        }
        for (const std::uint32_t i : {c.a, c.b}) {
            if (s.bodies[i].inv_mass != 0.0) predict_pairs_of(s, islands, i, slow, spent);
        }
    }
}

}  // namespace discreel::physics::detail
