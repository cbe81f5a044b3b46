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
// resolved here (that would become velocity) but left to project_positions. The friction row
// constrains the end velocity of the contact points (stick), within +- friction * normal impulse.
#include <algorithm>

#include "substep.hpp"

namespace discreel::physics::detail {
namespace {

V2 displacement_velocity(const Body& b) { return b.w_base + b.v * 0.5; }

}  // namespace

void solve_contacts(Substep& s, int iterations) {
    const double inv_h = 1.0 / s.h;
    for (Body& b : s.bodies) {
        if (b.falls()) b.v += s.gravity * s.h;
        b.w_base = b.v_begin * 0.5 + b.shift * inv_h;
    }
    for (const std::uint32_t index : s.active) {
        Contact& c = s.contacts[index];
        const Body& a = s.bodies[c.a];
        const Body& b = s.bodies[c.b];
        const V2 wa = displacement_velocity(a);
        const V2 wb = displacement_velocity(b);
        const V2 end_a = a.x + wa * s.h;
        const Feature* f = s.feature_of(c);
        const Proximity end = f ? disc_feature(end_a, a.radius, *f)
                                : disc_disc(end_a, a.radius, b.x + wb * s.h, b.radius);
        const double allowed_overlap = std::min(c.gap, 0.0);
        const V2& n = end.normal;
        c.normal = n;
        c.target_speed = n.dot(wa - wb) - (end.gap - allowed_overlap) / s.h;
        // Never ask for more than a restitution bounce: the pair must not leave faster than
        // e times its approach speed (after gravity, forces only ever stop a pair). Overlap that
        // this cannot prevent is removed by project_positions, without creating velocity.
        const double approach = n.dot(a.v_begin - b.v_begin);
        const double leave = std::max(0.0, -c.restitution * approach);
        const double capped = 0.5 * (approach + leave) + n.dot(a.shift - b.shift) / s.h;
        c.target_speed = std::min(c.target_speed, capped);
        const double k = normal_mass_inverse(a, b);
        c.normal_mass = k > 0.0 ? 1.0 / k : 0.0;
        c.tangent_mass = k > 0.0 ? 1.0 / tangent_mass_inverse(a, b) : 0.0;
    }
    for (const std::uint32_t index : s.active) {
        const Contact& c = s.contacts[index];
        apply_impulse(s.bodies[c.a], s.bodies[c.b], c.normal,
                      c.normal * c.normal_impulse + perp(c.normal) * c.tangent_impulse);
    }
    for (int it = 0; it < iterations; ++it) {
        for (const std::uint32_t index : s.active) {
            Contact& c = s.contacts[index];
            Body& a = s.bodies[c.a];
            Body& b = s.bodies[c.b];
            if (c.normal_mass == 0.0) continue;  // two immovable bodies
            const double wn =
                c.normal.dot(displacement_velocity(a) - displacement_velocity(b));
            const double dn = (c.target_speed - wn) * 2.0 * c.normal_mass;
            const double jn = std::max(c.normal_impulse + dn, 0.0);
            apply_impulse(a, b, c.normal, c.normal * (jn - c.normal_impulse));
            c.normal_impulse = jn;

            const double limit = c.friction * c.normal_impulse;
            const double dt = -tangential_speed(a, b, c.normal) * c.tangent_mass;
            const double jt = std::clamp(c.tangent_impulse + dt, -limit, limit);
            apply_impulse(a, b, c.normal, perp(c.normal) * (jt - c.tangent_impulse));
            c.tangent_impulse = jt;
        }
    }
    for (const std::uint32_t index : s.active) {
        Contact& c = s.contacts[index];
        c.step_impulse += c.normal_impulse;
    }
    for (std::size_t i = 0; i < s.disc_count; ++i) {
        Body& b = s.bodies[i];
        if (!b.moves()) continue;
        b.x += (b.v_begin + b.v) * (0.5 * s.h) + b.shift;
        b.angle += (b.omega_begin + b.omega) * (0.5 * s.h) + b.turn;
    }
}

void project_positions(Substep& s, int iterations) {
    for (int it = 0; it < iterations; ++it) {
        for (const std::uint32_t index : s.active) {
            const Contact& c = s.contacts[index];
            Body& a = s.bodies[c.a];
            Body& b = s.bodies[c.b];
            const double k = normal_mass_inverse(a, b);
            if (k == 0.0) continue;
            const Feature* f = s.feature_of(c);
            const Proximity p = f ? disc_feature(a.x, a.radius, *f)
                                  : disc_disc(a.x, a.radius, b.x, b.radius);
            // A sliver of overlap is left alone, so touching pairs are not nudged every substep.
            const double slop = 1e-4 * std::min(a.radius, f ? a.radius : b.radius);
            if (p.gap >= -slop) continue;
            const double push = 0.8 * (-p.gap - slop) / k;
            a.x += p.normal * (push * a.inv_mass);
            b.x -= p.normal * (push * b.inv_mass);
        }
    }
}

}  // namespace discreel::physics::detail
