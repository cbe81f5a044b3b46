// Strikes (body_solver.hpp): touching pairs that close faster than a settle speed at the
// step's start are collisions, not loads. Each is resolved on its own, two bodies at a time,
// before the rows, and every other touching pair of a body it moved is looked at again, so a
// blow travels down a row of touching bodies within one step, as the disc solver's impacts
// carry it (Newton's cradle): solved by the rows, every body of the row took a share and the
// striker bounced back. Slower closings are a pile's squeezes and stay with the rows.
#include <algorithm>
#include <cmath>
#include <optional>
#include <tuple>

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

std::optional<double> BodySolver::meets(const PairContact& pc, int k, const BlockBody& va,
                                        const BlockBody& vb, double settle, double dt) const {
    const double vn = normal_velocity(pc.contact, pc.contact.points[k], va, vb);
    if (vn >= -settle) return std::nullopt;
    const double gap = pc.anchors[static_cast<std::size_t>(k)].separation;
    if (gap <= 0) return 0.0;
    // A fast body's meetings are the impacts' (body_impacts.cpp), which sweep it from where
    // the step starts at its end velocity: a strike within the step would bend that path
    // (a gas of boxes at 30 m/s overlapped four times deeper).
    if (fast_[pc.a] || fast_[pc.b]) {
        return gap <= touch_distance(pc) ? std::optional<double>(0.0) : std::nullopt;
    }
    // A pair that meets within the step is a collision at that time, as the disc solver's
    // impacts time it: left to the rows, its speculative contact stopped the striker at the
    // touch by pushing the body it met, and through it every body touching that one (a
    // cradle whose striker arrived within a step shared the blow out: the last ball left at
    // 0.85 of the speed, the striker bounced back at 0.15).
    const double t = gap / -vn;
    return t < dt ? std::optional<double>(t) : std::nullopt;
}

std::optional<double> BodySolver::strikes_at(const PairContact& pc,
                                             const std::vector<Body>& bodies, double g,
                                             double dt) const {
    if (pc.restitution <= 0) return std::nullopt;
    const BlockBody va = start_velocity(bodies[pc.a]), vb = start_velocity(bodies[pc.b]);
    const double settle = strike_speed(pc, g, dt);
    std::optional<double> first;
    for (int k = 0; k < pc.contact.count; ++k) {
        const auto t = meets(pc, k, va, vb, settle, dt);
        if (t && (!first || *t < *first)) first = t;
    }
    return first;
}

void BodySolver::at_time(BlockContact& c, const PairContact& pc, const std::vector<Body>& bodies,
                         double t) const {
    // Where the bodies are at t, moving at their start velocities: each turned by omega t,
    // the normal with the body whose face it is (the line of centres between two circles), a
    // rounded shape's radius along it. Both bodies are struck at the one point midway between
    // their anchors, so that momentum and angular momentum are kept exactly.
    const Body& a = bodies[pc.a];
    const Body& b = bodies[pc.b];
    // A body struck earlier in the step moved at its old velocity until then: its shift.
    const V2 va = a.v - fall_, vb = b.v - fall_;
    const V2 xa = a.x + va * t + strike_shift_[pc.a], xb = b.x + vb * t + strike_shift_[pc.b];
    const auto turn = [&](const V2& r, double omega, std::uint32_t body) {
        const double angle = omega * t + strike_turn_[body];
        const double cs = std::cos(angle), sn = std::sin(angle);
        return V2(cs * r.x() - sn * r.y(), sn * r.x() + cs * r.y());
    };
    const bool round_a = shapes_[pc.a].count == 1, round_b = shapes_[pc.b].count == 1;
    V2 n = c.normal;
    if (round_a && round_b) {
        if ((xb - xa).norm() > 0) n = (xb - xa).normalized();
    } else {
        n = turn(c.normal, round_a ? b.omega : a.omega, round_a ? pc.b : pc.a);
    }
    const double ra_round = shapes_[pc.a].radius, rb_round = shapes_[pc.b].radius;
    for (int k = 0; k < c.count; ++k) {
        BlockPoint& p = c.points[k];
        const V2 on_a = xa + turn(p.ra - ra_round * c.normal, a.omega, pc.a) + ra_round * n;
        const V2 on_b = xb + turn(p.rb + rb_round * c.normal, b.omega, pc.b) - rb_round * n;
        const V2 mid = 0.5 * (on_a + on_b);
        p.ra = mid - xa;
        p.rb = mid - xb;
    }
    c.normal = n;
}

double BodySolver::strike(std::vector<Body>& bodies, const PairContact& pc, double t, double g,
                          double dt) {
    // Poisson's rule at the meeting points, as an impact (body_impacts.cpp). The impulses
    // are the collision's, not a lasting load: the contact's warm start is left as it was. A
    // point that does not meet is not struck (stopped, it would take an impulse the bodies
    // never exchanged).
    BlockBody va = start_velocity(bodies[pc.a]), vb = start_velocity(bodies[pc.b]);
    const double settle = strike_speed(pc, g, dt);
    BlockContact c = pc.contact;
    c.count = 0;
    for (int k = 0; k < pc.contact.count; ++k) {
        if (!meets(pc, k, va, vb, settle, dt)) continue;
        BlockPoint& p = c.points[c.count++];
        p = pc.contact.points[k];
        p.normal_impulse = 0;
        p.tangent_impulse = 0;
        p.target = 0;
    }
    if (t > 0) at_time(c, pc, bodies, t);
    const BlockBody before_a = va, before_b = vb;
    collide_poisson(c, va, vb, pc.restitution);
    double impulse = 0;
    for (int k = 0; k < c.count; ++k) impulse += c.points[k].normal_impulse;
    for (const auto& [i, s, before] :
         {std::tuple{pc.a, &va, &before_a}, std::tuple{pc.b, &vb, &before_b}}) {
        bodies[i].v = s->v + fall_;   // both can move, and are awake
        bodies[i].omega = s->omega;
        // Moving at its old velocity until t: it ends (v_before - v_after) t further on.
        if (t > 0) {
            strike_shift_[i] += (before->v - s->v) * t;
            strike_turn_[i] += (before->omega - s->omega) * t;
            shifted_ = true;
        }
        struck_at_[i] = t;
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
    if (shifted_) {
        std::fill(strike_shift_.begin(), strike_shift_.end(), V2::Zero());
        std::fill(strike_turn_.begin(), strike_turn_.end(), 0.0);
        shifted_ = false;
    }
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
        if (candidate(i) && strikes_at(fresh_[i], bodies, g, dt)) {
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
    struck_at_.assign(n, 0.0);
    strike_shift_.resize(n, V2::Zero());
    strike_turn_.resize(n, 0.0);
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
        if (strikes_of_[pc.a] >= limit || strikes_of_[pc.b] >= limit) continue;
        const auto meet = strikes_at(pc, bodies, g, dt);
        if (!meet) continue;
        // A blow passed on reaches the next pair when it struck the body between them.
        const double t = std::max({*meet, struck_at_[pc.a], struck_at_[pc.b]});
        struck_impulse_[i] += strike(bodies, pc, t, g, dt);
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
