// Continuous collision and restitution. Each substep, a pair that is approaching and meets
// within the substep (by the swept test in geometry.cpp, so a fast disc never passes through)
// gets the impulse j = -(1 + e) v_n / (1/m_a + 1/m_b) from its approach speed at the time of
// impact, with Coulomb friction. The bodies keep their pre-impact velocity up to that time,
// which Body::shift accounts for, so an isolated bounce is exact: no energy is gained or lost
// to the time discretisation. Impacts are swept pair by pair until none approaches, which lets
// a hit travel down a row of touching discs (Newton's cradle) instead of being shared out.
#include <algorithm>
#include <optional>

#include "substep.hpp"

namespace discreel::physics::detail {
namespace {

// Sweeps per substep. A hit travelling along a row of touching discs listed against its
// direction needs one sweep per disc; a dense heap of colliding discs would ping-pong for long.
// Whatever still approaches afterwards is handled by the resting stage (bounce of at most e).
constexpr int max_passes = 8;

// Approach speeds below this are rounding noise, not impacts. Approaches slower than what
// gravity adds in one substep are resting contact too: the resting stage handles them, still
// with a bounce of up to e times the approach speed, only without the time-of-impact timing.
// Left here, a pile would cost dozens of sweeps of micro-impacts per substep.
constexpr double min_approach_speed = 1e-9;  // m/s

Trajectory trajectory(const Substep& s, const Body& b) {
    return Trajectory{b.x + b.shift, b.v, s.gravity_on(b)};
}

// The impact of contact c in this substep, if its pair approaches faster than `slow` then.
std::optional<Impact> find_impact(const Substep& s, const Contact& c, double slow) {
    const Body& a = s.bodies[c.a];
    const Body& b = s.bodies[c.b];
    if (normal_mass_inverse(a, b) == 0.0) return std::nullopt;  // two immovable bodies
    const Feature* f = s.feature_of(c);
    if (!f && a.falls() == b.falls()) {
        // No relative acceleration: a pair moving apart along its centre line never meets,
        // and one slower than `slow` cannot approach faster than that.
        const V2 u = a.v - b.v;
        if (u.squaredNorm() <= slow * slow) return std::nullopt;
        if (((a.x + a.shift) - (b.x + b.shift)).dot(u) >= 0.0) return std::nullopt;
    }
    const double t_min = std::max(a.t_last, b.t_last);
    const Trajectory ta = trajectory(s, a);
    const std::optional<Impact> hit =
        f ? impact_disc_feature(ta, a.radius, *f, t_min, s.h)
          : impact_disc_disc(ta, a.radius, trajectory(s, b), b.radius, t_min, s.h);
    if (!hit) return std::nullopt;
    const V2 va = a.v + s.gravity_on(a) * hit->t;
    const V2 vb = b.v + s.gravity_on(b) * hit->t;
    if (hit->normal.dot(va - vb) >= -slow) return std::nullopt;
    return hit;
}

bool needs_check(const Contact& c, const std::vector<Body>& bodies, int pass) {
    // After the first sweep only pairs whose velocities just changed can start to approach.
    return pass == 0 || bodies[c.a].changed_pass >= pass - 1 || bodies[c.b].changed_pass >= pass - 1;
}

}  // namespace

void resolve_impacts(Substep& s) {
    const double slow = std::max(min_approach_speed, s.gravity.norm() * s.h);
    for (int pass = 0; pass < max_passes; ++pass) {
        // A body's impacts must happen in time order, or a later one computed first would move
        // it through the earlier one's wall: find each body's earliest impact first.
        for (Body& b : s.bodies) b.next_impact = s.h;
        for (const std::uint32_t index : s.active) {
            const Contact& c = s.contacts[index];
            if (!needs_check(c, s.bodies, pass)) continue;
            if (const auto hit = find_impact(s, c, slow)) {
                for (Body* body : {&s.bodies[c.a], &s.bodies[c.b]}) {
                    body->next_impact = std::min(body->next_impact, hit->t);
                }
            }
        }
        bool any = false;
        for (const std::uint32_t index : s.active) {
            Contact& c = s.contacts[index];
            if (!needs_check(c, s.bodies, pass)) continue;
            Body& a = s.bodies[c.a];
            Body& b = s.bodies[c.b];
            const std::optional<Impact> hit = find_impact(s, c, slow);
            if (!hit) continue;
            // An impact set off by another one in this sweep (a row of touching discs) happens
            // at that one's time, which is then this body's earliest; later ones wait a pass.
            if (hit->t > std::max(a.next_impact, a.t_last) ||
                hit->t > std::max(b.next_impact, b.t_last)) {
                // Make the next sweep look at this pair again.
                if (a.inv_mass > 0.0) a.changed_pass = pass;
                if (b.inv_mass > 0.0) b.changed_pass = pass;
                any = true;
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
                body->changed_pass = pass;
            }
            c.step_impulse += jn;
            any = true;
        }
        if (!any) break;
    }
}

}  // namespace discreel::physics::detail
