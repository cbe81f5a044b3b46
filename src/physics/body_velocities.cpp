// The velocity stages of the manifold solver's step (body_solver.hpp): the direct islands, the
// warm start and the coloured rows' iterations with the blocks of larger islands between them;
// then, once the positions have moved, the bounces.
#include <cmath>

#include "body_solver.hpp"
#include "discreel/physics.hpp"

namespace discreel::physics::detail {
namespace {

void store(RigidBody& b, const BlockBody& s) {
    b.v = s.v;
    b.omega = s.omega;
}

V2 rotate(const V2& v, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

}  // namespace

void BodySolver::solve_velocities(std::vector<RigidBody>& bodies) {
    // One more record than bodies: the scratch one the rows' empty lanes point at.
    state_.resize(bodies.size() + 1);
    for (std::size_t i = 0; i < bodies.size(); ++i) state_[i] = velocity_of(bodies[i]);
    state_.back() = BlockBody{};
    for_each_group(islands_, island_start_, [&](std::span<const IslandContact> island) {
        if (direct_solver_.velocities(island, state_)) return;
        // Not settled within its pivots (never seen): the island iterates like the others.
        for (const IslandContact& ic : island) direct_[ic.pair] = 0;
    });
    for (std::size_t i = 0; i < fresh_.size(); ++i) {
        PairContact& pc = fresh_[i];
        if (direct_[i]) continue;
        prepare_block(pc.contact, state_[pc.a], state_[pc.b]);
        apply_totals(pc, 1);
    }
    rows_.clear();
    for (std::size_t i = 0; i < fresh_.size(); ++i) {
        if (direct_[i] || blocked_[i]) continue;
        rows_.push_back(RowRef{fresh_[i].a, fresh_[i].b, &fresh_[i].contact});
    }
    block_rows_.build(rows_, state_);
    for (int it = 0; it < def_.iterations; ++it) {
        block_rows_.solve(state_);
        // A block's impulses are taken back out and solved again, together.
        for_each_group(blocks_, block_start_, [&](std::span<const IslandContact> block) {
            for (const IslandContact& ic : block) apply_totals(*pair_of(ic), -1);
            if (direct_solver_.velocities(block, state_)) return;
            for (const IslandContact& ic : block) apply_totals(*pair_of(ic), 1);
        });
    }
    block_rows_.store(rows_);
    for (std::size_t i = 0; i < bodies.size(); ++i) store(bodies[i], state_[i]);
}

void BodySolver::bounce(std::vector<RigidBody>& bodies, double settle) {
    const std::vector<double>& turned = turned_;
    // Restitution: points that arrived faster than settling and pushed this step leave at e
    // times their approach speed, both points of a manifold solved together (no spin from a
    // flat landing). Velocities only, frictionless, from the impulses already applied. The
    // bodies have moved: each point is taken midway between where its two anchors are now,
    // so that both bodies feel the impulse at one place and angular momentum is kept.
    for (std::size_t i = 0; i < fresh_.size(); ++i) {
        PairContact& pc = fresh_[i];
        BlockContact& c = pc.contact;
        bool bounce = false;
        for (int k = 0; k < c.count; ++k) {
            const double vn = pc.approach[static_cast<std::size_t>(k)];
            // A larger island of masses far apart does not bounce: its block iterations leave
            // light bodies rattling between heavy ones, and bouncing them by either rule pumps
            // energy in (heavy_light_bench's box; docs/tried.md).
            const bool hit = vn < -settle && c.points[k].normal_impulse > 0 && !blocked_[i];
            c.points[k].target = hit ? -pc.restitution * vn : 0;
            bounce = bounce || (hit && pc.restitution > 0);
        }
        if (!bounce && !direct_[i]) continue;
        for (int k = 0; k < c.count; ++k) {
            BlockPoint& p = c.points[k];
            const V2 ra = rotate(p.ra, turned[pc.a]), rb = rotate(p.rb, turned[pc.b]);
            const V2 point = 0.5 * ((bodies[pc.a].x + ra) + (bodies[pc.b].x + rb));
            p.ra = point - bodies[pc.a].x;
            p.rb = point - bodies[pc.b].x;
        }
        if (direct_[i]) continue;   // below, with its island
        prepare_block(c, state_[pc.a], state_[pc.b]);
        const double friction = c.friction;
        c.friction = 0;
        solve_block(c, state_[pc.a], state_[pc.b]);
        c.friction = friction;
    }
    // A direct island bounces by Poisson's rule: its points still closing are first stopped
    // together (the speculative solve let them close up to their gap), then each hit point gets
    // e times all the impulse that stopped it. Asking every point to leave at e times its
    // approach speed (Newton's rule, above) over-constrains a body struck at two places and
    // can add energy.
    const auto bounce_together = [&](std::span<const IslandContact> island) {
        const auto hit = [](const BlockPoint& p) { return p.target > 0; };   // and e > 0
        bool bounce = false;
        for (const IslandContact& ic : island) {
            for (int q = 0; q < ic.contact->count; ++q) bounce = bounce || hit(ic.contact->points[q]);
        }
        if (!bounce || !direct_solver_.stop(island, state_, push_)) return;
        std::size_t point = 0;
        for (const IslandContact& ic : island) {
            const PairContact& pc = *pair_of(ic);
            for (int q = 0; q < ic.contact->count; ++q, ++point) {
                BlockPoint& p = ic.contact->points[q];
                double impulse = push_[point];
                if (hit(p)) impulse += pc.restitution * (p.normal_impulse + push_[point]);
                apply_impulse(state_[pc.a], state_[pc.b], p, impulse * ic.contact->normal);
                p.normal_impulse += impulse;
            }
        }
        // A bounce drives its bodies into their other contacts, which did not arrive (a light
        // body between a heavy one landing on it and the floor would leave through the floor
        // at e times the heavy one's momentum): they are stopped again, together, which only
        // takes energy out. Those impulses answer this bounce, not a lasting load, so they are
        // not kept for the next step's warm start (kept, they launched light bodies there).
        if (!direct_solver_.stop(island, state_, push_)) return;
        point = 0;
        for (const IslandContact& ic : island) {
            const PairContact& pc = *pair_of(ic);
            for (int q = 0; q < ic.contact->count; ++q, ++point) {
                const BlockPoint& p = ic.contact->points[q];
                apply_impulse(state_[pc.a], state_[pc.b], p, push_[point] * ic.contact->normal);
            }
        }
    };
    for_each_group(islands_, island_start_, bounce_together);
    for (std::size_t i = 0; i < bodies.size(); ++i) store(bodies[i], state_[i]);

}

}  // namespace discreel::physics::detail
