#include "body_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "discreel/physics.hpp"

namespace discreel::physics::detail {
namespace {

BlockBody velocity_of(const RigidBody& b) {
    return {.v = b.v, .omega = b.omega, .inv_mass = b.inv_mass, .inv_inertia = b.inv_inertia};
}

void store(RigidBody& b, const BlockBody& s) {
    b.v = s.v;
    b.omega = s.omega;
}

void apply_impulse(BlockBody& a, BlockBody& b, const BlockPoint& p, const V2& impulse) {
    a.v -= a.inv_mass * impulse;
    a.omega -= a.inv_inertia * cross(p.ra, impulse);
    b.v += b.inv_mass * impulse;
    b.omega += b.inv_inertia * cross(p.rb, impulse);
}

}  // namespace

void BodySolver::step(std::vector<RigidBody>& bodies, const V2& gravity, double dt) {
    for (RigidBody& b : bodies) {
        if (b.inv_mass > 0) b.v += gravity * dt;
    }
    // Restitution acts on approaches faster than gravity gives in about two steps: slower
    // ones are a body settling, which would otherwise hop by e g dt every step.
    const double settle = 2 * gravity.norm() * dt;

    std::vector<double> reach(bodies.size());   // bounding radius plus the speculative distance
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        reach[i] = bounding_radius(bodies[i].shape) + 0.5 * def_.speculative;
    }
    std::vector<PairContact> fresh;
    std::vector<double> restitution;                 // per pair
    std::vector<std::array<double, 2>> approach;     // per point: normal velocity before, m/s
    for (std::uint32_t i = 0; i < bodies.size(); ++i) {
        for (std::uint32_t j = i + 1; j < bodies.size(); ++j) {
            const RigidBody& a = bodies[i];
            const RigidBody& b = bodies[j];
            if (a.inv_mass == 0 && b.inv_mass == 0) continue;
            const double r = reach[i] + reach[j];
            if ((a.x - b.x).squaredNorm() > r * r) continue;   // bounding circles apart
            PairContact pc{.a = i, .b = j, .manifold = {}, .contact = {}};
            pc.manifold = collide(a.shape, Transform::of(a.x, a.angle), b.shape,
                                  Transform::of(b.x, b.angle), def_.speculative);
            if (pc.manifold.count == 0) continue;
            BlockContact& c = pc.contact;
            c.normal = pc.manifold.normal;
            c.count = pc.manifold.count;
            c.friction = mix_friction(a.friction, b.friction);
            restitution.push_back(mix_restitution(a.restitution, b.restitution));
            approach.push_back({0, 0});
            // Warm start: the impulses of the same features last step.
            const auto by_pair = [](const PairContact& x, const PairContact& y) {
                return x.a != y.a ? x.a < y.a : x.b < y.b;
            };
            const auto previous =
                std::lower_bound(contacts_.begin(), contacts_.end(), pc, by_pair);
            const bool had = previous != contacts_.end() && previous->a == i && previous->b == j;
            BlockBody va = velocity_of(a), vb = velocity_of(b);
            for (int k = 0; k < c.count; ++k) {
                const ManifoldPoint& mp = pc.manifold.points[k];
                BlockPoint& p = c.points[k];
                p.ra = mp.point - a.x;
                p.rb = mp.point - b.x;
                // Apart: approach at most far enough to touch within the step; touching: stop
                // closing. The bounce comes after the positions move (below), so that a body
                // leaves from the surface at e times the speed it arrived with.
                p.target = mp.separation > 0 ? -mp.separation / dt : 0;
                approach.back()[static_cast<std::size_t>(k)] = normal_velocity(c, p, va, vb);
                if (!had) continue;
                for (int q = 0; q < previous->contact.count; ++q) {
                    if (previous->manifold.points[q].id != mp.id) continue;
                    p.normal_impulse = previous->contact.points[q].normal_impulse;
                    p.tangent_impulse = previous->contact.points[q].tangent_impulse;
                }
            }
            fresh.push_back(pc);
        }
    }

    // Warm start, then the velocity iterations, body states carried between contacts.
    std::vector<BlockBody> state(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) state[i] = velocity_of(bodies[i]);
    for (PairContact& pc : fresh) {
        const V2 tangent = -perp(pc.contact.normal);
        for (int k = 0; k < pc.contact.count; ++k) {
            const BlockPoint& p = pc.contact.points[k];
            apply_impulse(state[pc.a], state[pc.b], p,
                          p.normal_impulse * pc.contact.normal + p.tangent_impulse * tangent);
        }
    }
    for (int it = 0; it < def_.iterations; ++it) {
        for (PairContact& pc : fresh) solve_block(pc.contact, state[pc.a], state[pc.b]);
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) store(bodies[i], state[i]);

    for (RigidBody& b : bodies) {
        b.x += b.v * dt;
        b.angle += b.omega * dt;
    }

    // Restitution: points that arrived faster than settling and pushed this step leave at e
    // times their approach speed, both points of a manifold solved together (no spin from a
    // flat landing). Velocities only, frictionless, from the impulses already applied.
    for (std::size_t n = 0; n < fresh.size(); ++n) {
        BlockContact& c = fresh[n].contact;
        bool bounce = false;
        for (int k = 0; k < c.count; ++k) {
            const double vn = approach[n][static_cast<std::size_t>(k)];
            const bool hit = vn < -settle && c.points[k].normal_impulse > 0;
            c.points[k].target = hit ? -restitution[n] * vn : 0;
            bounce = bounce || (hit && restitution[n] > 0);
        }
        if (!bounce) continue;
        const double friction = c.friction;
        c.friction = 0;
        solve_block(c, state[fresh[n].a], state[fresh[n].b]);
        c.friction = friction;
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) store(bodies[i], state[i]);

    // Whatever overlap is left beyond the slop is pushed out, point by point, on fresh
    // manifolds: positions only, so no velocity (and no energy) is added.
    for (int sweep = 0; sweep < def_.position_iterations; ++sweep) {
        for (const PairContact& pc : fresh) {
            RigidBody& a = bodies[pc.a];
            RigidBody& b = bodies[pc.b];
            const Manifold m = collide(a.shape, Transform::of(a.x, a.angle), b.shape,
                                       Transform::of(b.x, b.angle), 0);
            for (int k = 0; k < m.count; ++k) {
                const double overlap = m.points[k].separation + def_.slop;
                if (overlap >= 0) continue;
                const double push = std::min(-overlap, def_.max_correction);
                const V2 ra = m.points[k].point - a.x, rb = m.points[k].point - b.x;
                const double rna = cross(ra, m.normal), rnb = cross(rb, m.normal);
                const double k_n = a.inv_mass + b.inv_mass + a.inv_inertia * rna * rna +
                                   b.inv_inertia * rnb * rnb;
                if (k_n <= 0) continue;
                const V2 impulse = (push / k_n) * m.normal;
                a.x -= a.inv_mass * impulse;
                a.angle -= a.inv_inertia * cross(ra, impulse);
                b.x += b.inv_mass * impulse;
                b.angle += b.inv_inertia * cross(rb, impulse);
            }
        }
    }
    contacts_ = std::move(fresh);
}

}  // namespace discreel::physics::detail
