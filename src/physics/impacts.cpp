// Continuous collision and restitution. Each substep, a pair that is approaching and meets
// within the substep (by the swept test in geometry.cpp, so a fast disc never passes through)
// gets the impulse j = -(1 + e) v_n / (1/m_a + 1/m_b) from its approach speed at the time of
// impact, with Coulomb friction. The bodies keep their pre-impact velocity up to that time,
// which Body::shift accounts for, so an isolated bounce is exact: no energy is gained or lost
// to the time discretisation. Impacts are swept pair by pair until none approaches, which lets
// a hit travel down a row of touching discs (Newton's cradle) instead of being shared out.
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>

#include "substep.hpp"

namespace discreel::physics::detail {
namespace {

// Sweeps per substep. A hit travelling along a row of touching discs listed against its
// direction needs one sweep per disc; a dense heap of colliding discs would ping-pong for long.
// Whatever still approaches afterwards is handled by the resting stage (bounce of at most e).
constexpr int max_passes = 8;
constexpr int max_sweeps = 4096;

// Approach speeds below this are rounding noise, not impacts. Approaches slower than what
// gravity adds in one substep are resting contact too: the resting stage handles them, still
// with a bounce of up to e times the approach speed, only without the time-of-impact timing.
// Left here, a pile would cost dozens of sweeps of micro-impacts per substep.
constexpr double min_approach_speed = 1e-9;  // m/s

// Such a pair is timed only if its bounce would be worth it: leaving fast enough (e times its
// approach speed) to rise `visible_bounce` radii against gravity ((e v)^2 / 2|g| = f r), or
// approaching fast enough to close `closing_step` radii within the substep. A landing heap has
// hundreds of slower squeezes per substep, each fanning out over several sweeps; the resting
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
// before it are inlined into the sweeps (a settled pile never gets here).
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
    // Radii, gravity and the substep's length never change within a world.
    if (settle_.size() != s.disc_count || settle_h_ != s.h) {
        settle_h_ = s.h;
        next_impact_.assign(s.bodies.size(), s.h);
        settle_.resize(s.disc_count);
        for (std::size_t i = 0; i < s.disc_count; ++i) {
            const double r = s.bodies[i].radius;
            settle_[i] = Settle{std::sqrt(2.0 * visible_bounce * s.gravity.norm() * r),
                                closing_step * r / s.h};
        }
    }
}

void ImpactResolver::resolve(Substep& s) {
    const double slow = slow_;
    const std::size_t count = s.active.size();
    changed_.clear();
    // Each sweep after the first visits only the pairs of discs struck in the one before, so a
    // few discs ping-ponging fast (a light disc between a heavy one and a wall needs about
    // pi sqrt(M/m) bounces) get many sweeps, while a heap colliding everywhere at once stops
    // after max_passes full sweeps' worth of work.
    const std::size_t budget = static_cast<std::size_t>(max_passes) * std::max<std::size_t>(count, 64);
    std::size_t spent = 0;
    // found_ and queued_ are stamped with sweep numbers that never repeat, so that no sweep
    // resets them: a landing heap has impacts in almost every substep, and clearing a record
    // per active contact in each of them would be a pass over all the contacts.
    const std::uint64_t first_sweep = sweeps_done_;
    if (found_.size() < count) {
        found_.resize(count);
        queued_.resize(count, never);
    }
    for (int pass = 0; spent < budget && pass < max_sweeps; ++pass) {
        const std::uint64_t sweep = first_sweep + static_cast<std::uint64_t>(pass);
        sweeps_done_ = sweep + 1;
        // This sweep's pairs, in active order: those that screen() did not rule out first, then
        // those of bodies changed in the previous sweep.
        candidates_.clear();
        if (pass == 0) {
            candidates_.swap(screened_);
        } else {
            for (const std::uint32_t body : changed_) {
                for (std::uint32_t e = contacts_of_start_[body]; e < contacts_of_start_[body + 1];
                     ++e) {
                    std::uint32_t k;
                    if (!active_position(contacts_of_[e], k) || queued_[k] == sweep) continue;
                    queued_[k] = sweep;
                    candidates_.push_back(k);
                }
            }
            std::sort(candidates_.begin(), candidates_.end());
        }
        changed_.clear();
        spent += pass == 0 ? count : candidates_.size();

        // A body's impacts must happen in time order, or a later one computed first would move
        // it through the earlier one's wall: find each body's earliest impact first.
        lowered_.clear();
        for (const std::uint32_t k : candidates_) {
            const Contact& c = s.contacts[s.active[k]];
            // No body has changed since screen() passed the first sweep's pairs.
            const std::optional<Impact> hit = pass == 0
                                                  ? swept_impact(s, c, slowest_impact(s, c, slow))
                                                  : find_impact(s, c, slow);
            // The first sweep answers for every active pair, so only its hits are recorded:
            // the others, tested or ruled out by screen(), have none (see `known` below).
            if (pass > 0 || hit) found_[k] = FoundImpact{sweep, hit};
            if (!hit) continue;
            for (const std::uint32_t i : {c.a, c.b}) {
                if (next_impact_[i] == s.h) lowered_.push_back(i);
                next_impact_[i] = std::min(next_impact_[i], hit->t);
            }
        }

        // A settled pile has no impacts at all.
        if (pass == 0) {
            if (lowered_.empty()) break;
            // The pairs ruled out are listed too when an impact of this sweep changes a body.
            for (const std::uint32_t k : candidates_) queued_[k] = sweep;
        }

        // Visited in active order; a body changed during this sweep adds its later pairs to it
        // (a hit travelling down a row of touching discs listed in order), kept in a min-heap
        // merged with the sorted candidates.
        queue_.clear();
        auto mark_changed = [&](std::uint32_t i, std::uint32_t after) {
            Body& body = s.bodies[i];
            if (body.inv_mass == 0.0 || body.changed_pass == pass) return;
            // Changed in the previous sweep: all its pairs are listed.
            const bool already_queued = pass > 0 && body.changed_pass == pass - 1;
            body.changed_pass = pass;
            changed_.push_back(i);
            if (already_queued) return;
            for (std::uint32_t e = contacts_of_start_[i]; e < contacts_of_start_[i + 1]; ++e) {
                std::uint32_t k;
                if (!active_position(contacts_of_[e], k) || k <= after || queued_[k] == sweep) {
                    continue;
                }
                queued_[k] = sweep;
                queue_.push_back(k);
                std::push_heap(queue_.begin(), queue_.end(), std::greater<>());
            }
        };
        bool any = false;
        std::size_t next_candidate = 0;
        while (next_candidate < candidates_.size() || !queue_.empty()) {
            std::uint32_t k;
            if (queue_.empty() ||
                (next_candidate < candidates_.size() && candidates_[next_candidate] < queue_[0])) {
                k = candidates_[next_candidate++];
            } else {
                std::pop_heap(queue_.begin(), queue_.end(), std::greater<>());
                k = queue_.back();
                queue_.pop_back();
            }
            Contact& c = s.contacts[s.active[k]];
            Body& a = s.bodies[c.a];
            Body& b = s.bodies[c.b];
            // The answer found above still holds unless an impact of this sweep moved a or b.
            const FoundImpact& found = found_[k];
            const bool recorded = found.sweep == sweep;
            const bool known = recorded || pass == 0;
            const std::optional<Impact> hit =
                known && a.struck_pass != pass && b.struck_pass != pass
                    ? (recorded ? found.hit : std::nullopt)
                    : find_impact(s, c, slow);
            if (!hit) continue;
            any = true;
            // An impact set off by another one in this sweep (a row of touching discs) happens
            // at that one's time, which is then this body's earliest; later ones wait a pass.
            if (hit->t > std::max(next_impact_[c.a], a.t_last) ||
                hit->t > std::max(next_impact_[c.b], b.t_last)) {
                // Make the next sweep look at this pair again.
                mark_changed(c.a, k);
                mark_changed(c.b, k);
                continue;
            }
            const V2& n = hit->normal;
            const V2 va = a.v + s.gravity_on(a) * hit->t;
            const V2 vb = b.v + s.gravity_on(b) * hit->t;
            const double vn = n.dot(va - vb);
            const double jn = -(1.0 + c.restitution) * vn / normal_mass_inverse(a, b);
            const double vt = perp(n).dot(va - vb) - a.radius * a.omega - b.radius * b.omega;
            const double limit = c.friction * jn;
            const double jt = std::clamp(-vt / tangent_mass_inverse(a, b), -limit, limit);

            const V2 va0 = a.v, vb0 = b.v;
            const double wa0 = a.omega, wb0 = b.omega;
            apply_impulse(a, b, n, n * jn + perp(n) * jt);
            a.shift -= (a.v - va0) * hit->t;
            b.shift -= (b.v - vb0) * hit->t;
            a.turn -= (a.omega - wa0) * hit->t;
            b.turn -= (b.omega - wb0) * hit->t;
            // Walls, pegs and held discs keep their motion, so they carry no impact history.
            for (Body* body : {&a, &b}) {
                if (body->inv_mass == 0.0) continue;
                body->t_last = std::max(body->t_last, hit->t);
                body->struck_pass = pass;
            }
            mark_changed(c.a, k);
            mark_changed(c.b, k);
            c.step_impulse += jn;
        }
        for (const std::uint32_t i : lowered_) next_impact_[i] = s.h;
        if (!any) break;
    }
}

}  // namespace discreel::physics::detail
