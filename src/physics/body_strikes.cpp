// Strikes (body_solver.hpp): touching pairs that close faster than a settle speed at the
// step's start are collisions, not loads. Each is resolved on its own, two bodies at a time,
// before the rows, and every other touching pair of a body it moved is looked at again, so a
// blow travels down a row of touching bodies within one step, as the disc solver's impacts
// carry it (Newton's cradle): solved by the rows, every body of the row took a share and the
// striker bounced back. Slower closings are a pile's squeezes and stay with the rows.
#include <algorithm>
#include <cmath>

#include "body_solver.hpp"
#include "discreel/physics.hpp"

namespace discreel::physics::detail {

double BodySolver::strike_speed(const PairContact& pc, double g, double dt) const {
    // The disc solver's settle speed (docs/physics.md), for the smaller inner radius r: under
    // |g| dt a closing is gravity's own; a bounce under sqrt(0.1 |g| r) / e would rise under
    // 5 % of r, and a squeeze under 0.02 r / dt closes under 2 % of r in the step.
    // Without gravity all three are 0: closings at rounding's level are still not blows (the
    // disc solver's impacts have the same floor).
    constexpr double rounding = 1e-9;   // m/s
    const double r = std::min(inner_[pc.a], inner_[pc.b]);
    return std::max({rounding, g * dt,
                     std::min(std::sqrt(0.1 * g * r) / pc.restitution, 0.02 * r / dt)});
}

double BodySolver::touch_distance(const PairContact& pc) const {
    // The disc solver's measure of touching: within 0.5 % of the smaller inner radius.
    return 0.005 * std::min(inner_[pc.a], inner_[pc.b]);
}

BlockBody BodySolver::start_velocity(const Body& b) const {
    BlockBody s = velocity_of(b);
    if (b.inv_mass > 0 && !b.asleep) s.v -= fall_;
    return s;
}

bool BodySolver::strikes_now(const PairContact& pc, const std::vector<Body>& bodies, double g,
                             double dt) const {
    if (pc.restitution <= 0) return false;
    const double touch = touch_distance(pc);
    const BlockBody va = start_velocity(bodies[pc.a]), vb = start_velocity(bodies[pc.b]);
    const double settle = strike_speed(pc, g, dt);
    for (int k = 0; k < pc.contact.count; ++k) {
        if (pc.anchors[static_cast<std::size_t>(k)].separation > touch) continue;
        if (normal_velocity(pc.contact, pc.contact.points[k], va, vb) < -settle) return true;
    }
    return false;
}

double BodySolver::strike(std::vector<Body>& bodies, const PairContact& pc) {
    // Poisson's rule at the touching points, as an impact (body_impacts.cpp). The impulses
    // are the collision's, not a lasting load: the contact's warm start is left as it was. A
    // point still apart is not struck (stopped, it would take an impulse the bodies never
    // exchanged).
    const double touching = touch_distance(pc);
    BlockContact c = pc.contact;
    c.count = 0;
    for (int k = 0; k < pc.contact.count; ++k) {
        if (pc.anchors[static_cast<std::size_t>(k)].separation > touching) continue;
        BlockPoint& p = c.points[c.count++];
        p = pc.contact.points[k];
        p.normal_impulse = 0;
        p.tangent_impulse = 0;
        p.target = 0;
    }
    BlockBody va = start_velocity(bodies[pc.a]), vb = start_velocity(bodies[pc.b]);
    collide_poisson(c, va, vb, pc.restitution);
    double impulse = 0;
    for (int k = 0; k < c.count; ++k) impulse += c.points[k].normal_impulse;
    for (const auto& [i, s] : {std::pair{pc.a, &va}, std::pair{pc.b, &vb}}) {
        bodies[i].v = s->v + fall_;   // both can move, and are awake
        bodies[i].omega = s->omega;
    }
    return impulse;
}

void BodySolver::strike_touching(std::vector<Body>& bodies, const V2& gravity, double dt) {
    // The pairs touch at the step's start: they meet with the velocities they had then, and
    // this step's gravity (begin_step's) acts after the strike. Struck with it included, a
    // body would leave at e (v + g dt) where e v - g dt is due: a ball dropped 10 cm onto
    // another would rise 8 % too high.
    const double g = gravity.norm();
    struck_impulse_.assign(fresh_.size(), 0);
    // Only in a world whose moving bodies are all within direct_mass_ratio of each other:
    // where masses are far apart, islands are solved together, and pairs of alike bodies
    // struck one by one beside them drove light boxes deep into heavy ones (limits_bench
    // boxes, 1e6 at 1 radius per step: deepest overlap 188 -> 517 %).
    if (!even_world_) return;
    // Two bodies that can move: against a wall or a held body the speculative contact and
    // the bounce after the positions do better (an elastic ball struck at the floor whenever
    // a step ended just short of it kept 91 % of its height after 10 s of bouncing; bounced,
    // 96 %: both lose it to the step's integration, which is not the exact parabola).
    const auto candidate = [&](std::size_t i) {
        const PairContact& pc = fresh_[i];
        return pc.restitution > 0 && bodies[pc.a].inv_mass > 0 && bodies[pc.b].inv_mass > 0;
    };
    queue_.clear();
    for (std::size_t i = 0; i < fresh_.size(); ++i) {
        if (candidate(i) && strikes_now(fresh_[i], bodies, g, dt)) {
            queue_.push_back(static_cast<std::uint32_t>(i));
        }
    }
    if (queue_.empty()) return;
    // Each body's contacts, to look at again once a strike moved it.
    const std::size_t n = bodies.size();
    contact_start_.assign(n + 1, 0);
    for (const PairContact& pc : fresh_) {
        ++contact_start_[pc.a + 1];
        ++contact_start_[pc.b + 1];
    }
    for (std::size_t i = 0; i < n; ++i) contact_start_[i + 1] += contact_start_[i];
    contacts_of_.resize(contact_start_[n]);
    {
        std::vector<std::uint32_t>& next = strikes_of_;   // as a fill cursor here
        next.assign(contact_start_.begin(), contact_start_.end() - 1);
        for (std::size_t i = 0; i < fresh_.size(); ++i) {
            contacts_of_[next[fresh_[i].a]++] = static_cast<std::uint32_t>(i);
            contacts_of_[next[fresh_[i].b]++] = static_cast<std::uint32_t>(i);
        }
    }
    strikes_of_.assign(n, 0);
    queued_.assign(fresh_.size(), 0);
    for (const std::uint32_t i : queue_) queued_[i] = 1;
    struck_.assign(n, 0);
    // In pair order, then in the order the blows reach them; at most strikes_per_body per
    // body and step, so a crowd's chain of blows is bounded (the rows take what is left).
    const auto limit = static_cast<std::uint32_t>(std::max(0, def_.strikes_per_body));
    for (std::size_t q = 0; q < queue_.size(); ++q) {
        const std::uint32_t i = queue_[q];
        queued_[i] = 0;
        const PairContact& pc = fresh_[i];
        if (strikes_of_[pc.a] >= limit || strikes_of_[pc.b] >= limit ||
            !strikes_now(pc, bodies, g, dt)) {
            continue;
        }
        struck_impulse_[i] += strike(bodies, pc);
        for (const std::uint32_t body : {pc.a, pc.b}) {
            ++strikes_of_[body];
            struck_[body] = 1;
            for (std::uint32_t k = contact_start_[body]; k < contact_start_[body + 1]; ++k) {
                const std::uint32_t other = contacts_of_[k];
                if (queued_[other] || !candidate(other)) continue;
                queued_[other] = 1;
                queue_.push_back(other);
            }
        }
    }
    // The bounce after the positions looks at the approach a pair had before the rows
    // (gravity's included): a struck body's pairs approach as the strikes left them.
    for (PairContact& pc : fresh_) {
        if (!struck_[pc.a] && !struck_[pc.b]) continue;
        const BlockBody va = velocity_of(bodies[pc.a]), vb = velocity_of(bodies[pc.b]);
        for (int k = 0; k < pc.contact.count; ++k) {
            pc.approach[static_cast<std::size_t>(k)] =
                normal_velocity(pc.contact, pc.contact.points[k], va, vb);
        }
    }
}

}  // namespace discreel::physics::detail
