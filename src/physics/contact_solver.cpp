// Resting contact. Contact impulses here stand for forces spread over the substep (gravity,
// weight of a pile, friction while sliding), so, like gravity, an impulse dv moves a body by
// dv h / 2 within the substep: positions advance by the mean of the substep's start and end
// velocities. A disc resting on the floor then ends every substep exactly where it began with
// zero velocity, and a free disc follows the exact parabola.
//
// The normal row therefore constrains the displacement velocity w = (v_begin + v) / 2 + shift / h
// so that the gap at the end of the substep is not negative. It is linearised around where the
// pair would end up without contact forces, not where it starts: a constraint acts only if the
// pair would actually overlap by then, so discs grazing past each other feel nothing (a
// start-of-substep normal would push them apart and add energy). Existing overlap is not
// resolved here (that would become velocity) but left to PositionProjector. The friction row
// constrains the end velocity of the contact points (stick), within +- friction * normal impulse.
// The iterations only read and write velocities, so they run on a compact copy: one row per
// contact with everything constant over the substep folded in (normal, masses, the part of the
// displacement velocity fixed by the impulsive stage), and one small velocity record per body.
// That keeps the hot loop inside a few cache lines per contact, even for 10 000 discs.
#include <algorithm>

#include "substep.hpp"

namespace discreel::physics::detail {

void ContactSolver::solve(Substep& s, int iterations) {
    const double inv_h = 1.0 / s.h;
    velocities_.resize(s.bodies.size());
    for (std::size_t i = 0; i < s.bodies.size(); ++i) {
        Body& b = s.bodies[i];
        if (b.falls()) b.v += s.gravity * s.h;
        b.w_base = b.v_begin * 0.5 + b.shift * inv_h;
        velocities_[i] = Velocity{b.v, b.omega};
    }

    rows_.clear();
    for (const std::uint32_t index : s.active) {
        Contact& c = s.contacts[index];
        const Body& a = s.bodies[c.a];
        const Body& b = s.bodies[c.b];
        const double k = normal_mass_inverse(a, b);
        if (k == 0.0) continue;  // two immovable bodies: nothing to solve
        // Displacement velocity w = w_base + v / 2 (see the top of this file).
        const V2 wa = a.w_base + a.v * 0.5;
        const V2 wb = b.w_base + b.v * 0.5;
        const V2 end_a = a.x + wa * s.h;
        const Feature* f = s.feature_of(c);
        const Proximity end = f ? disc_feature(end_a, a.radius, *f)
                                : disc_disc(end_a, a.radius, b.x + wb * s.h, b.radius);
        const double allowed_overlap = std::min(c.gap, 0.0);
        const V2& n = end.normal;
        double target = n.dot(wa - wb) - (end.gap - allowed_overlap) * inv_h;
        // Never ask for more than a restitution bounce: the pair must not leave faster than
        // e times its approach speed (after gravity, forces only ever stop a pair). Overlap that
        // this cannot prevent is removed by PositionProjector, without creating velocity.
        const double approach = n.dot(a.v_begin - b.v_begin);
        const double leave = std::max(0.0, -c.restitution * approach);
        const double capped = 0.5 * (approach + leave) + n.dot(a.shift - b.shift) * inv_h;
        target = std::min(target, capped);

        Row r;
        r.a = c.a;
        r.b = c.b;
        r.contact = index;
        r.normal = n;
        // The row drives n.(w_a - w_b) = n.(w_base_a - w_base_b) + n.(v_a - v_b) / 2 up to the
        // target; only v changes while iterating, so the rest is folded into the bias.
        r.bias = 2.0 * (target - n.dot(a.w_base - b.w_base));
        r.normal_mass = 1.0 / k;
        r.tangent_mass = 1.0 / tangent_mass_inverse(a, b);
        r.friction = c.friction;
        r.inv_mass_a = a.inv_mass;
        r.inv_mass_b = b.inv_mass;
        r.radius_a = a.radius;
        r.radius_b = b.radius;
        r.spin_a = a.radius * a.inv_inertia;
        r.spin_b = b.radius * b.inv_inertia;
        r.normal_impulse = c.normal_impulse;
        r.tangent_impulse = c.tangent_impulse;
        rows_.push_back(r);
    }

    // Warm start, then sequential impulses. A normal impulse passes through the centres, so
    // only tangential impulses turn the discs.
    for (const Row& r : rows_) {
        Velocity& a = velocities_[r.a];
        Velocity& b = velocities_[r.b];
        const V2 p = r.normal * r.normal_impulse + perp(r.normal) * r.tangent_impulse;
        a.v += p * r.inv_mass_a;
        b.v -= p * r.inv_mass_b;
        a.omega -= r.spin_a * r.tangent_impulse;
        b.omega -= r.spin_b * r.tangent_impulse;
    }
    // Both rows of a contact are solved from the same velocities: a normal impulse passes
    // through the centres along n, so it leaves the tangential relative velocity unchanged and
    // the friction row need not wait for it. One update per body per contact, and a dependency
    // chain half as long as solving the rows one after the other.
    for (int it = 0; it < iterations; ++it) {
        for (Row& r : rows_) {
            Velocity& a = velocities_[r.a];
            Velocity& b = velocities_[r.b];
            const V2& n = r.normal;
            const V2 t = perp(n);
            const V2 dv = a.v - b.v;
            const double vn = n.dot(dv);
            const double vt = t.dot(dv) - r.radius_a * a.omega - r.radius_b * b.omega;
            const double jn = std::max(r.normal_impulse + (r.bias - vn) * r.normal_mass, 0.0);
            const double limit = r.friction * jn;
            const double jt = std::clamp(r.tangent_impulse - vt * r.tangent_mass, -limit, limit);
            const double dn = jn - r.normal_impulse;
            const double dt = jt - r.tangent_impulse;
            const V2 p = n * dn + t * dt;
            a.v += p * r.inv_mass_a;
            b.v -= p * r.inv_mass_b;
            a.omega -= r.spin_a * dt;
            b.omega -= r.spin_b * dt;
            r.normal_impulse = jn;
            r.tangent_impulse = jt;
        }
    }

    for (const Row& r : rows_) {
        Contact& c = s.contacts[r.contact];
        c.normal_impulse = r.normal_impulse;
        c.tangent_impulse = r.tangent_impulse;
    }
    for (const std::uint32_t index : s.active) {
        Contact& c = s.contacts[index];
        c.step_impulse += c.normal_impulse;
    }
    for (std::size_t i = 0; i < s.disc_count; ++i) {
        Body& b = s.bodies[i];
        if (!b.moves()) continue;
        b.v = velocities_[i].v;
        b.omega = velocities_[i].omega;
        b.x += (b.v_begin + b.v) * (0.5 * s.h) + b.shift;
        b.angle += (b.omega_begin + b.omega) * (0.5 * s.h) + b.turn;
    }
}

}  // namespace discreel::physics::detail
