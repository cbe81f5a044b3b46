// Continuous collision between moving bodies in the manifold solver. A speculative contact
// (body_solver.cpp) stops a pair along the normal seen where the step starts and bounces it at
// the step's end; a body that travels more than `impact_travel` of its inner radius in a step
// can meet features that were not the nearest then (a corner swinging past a corner, two boxes
// crossing diagonally) and pass through, and its bounce would come late. So a fast body's pairs
// that start apart with masses alike are left out of the solve, and after it every pair with a
// fast body (or one that ended deeper in than the solve should allow) is swept from where the
// step started to where it ended. Its first touch, by conservative advancement (toi.hpp), is an
// impact: both bodies are put where they were then (circles, and a body standing still, carried
// on from the advancement's gap to the touch), the pair's manifold there is stopped by the
// two-point block solve and bounced by Poisson's rule, and both move on at their new velocities
// for the rest of the step, so no time is lost (Box2D v3 stops a bullet at its time of impact
// for the rest of the step). A pair touching where its sweep starts is an impact at once if it
// closes where it touches, or when it would sink in by more than the slop before the step ends.
// Impacts are taken in order of time, then pair; each re-predicts only its two bodies' pairs.
// At most `impacts_per_fast_body` per fast body and step: beyond, a body still to meet
// something stops where it would meet it, losing the rest of its step.
#include <algorithm>
#include <cmath>
#include <optional>

#include "body_solver.hpp"
#include "discreel/physics.hpp"

namespace discreel::physics::detail {
namespace {

// The surfaces are stopped this far apart (metres, at most; less for small bodies), and a
// distance within twice it is a touch: close enough that the gap never shows, far enough that
// advancement converges in a few iterations.
constexpr double impact_gap = 1.25e-4;

std::array<double, 4> swept_box(const Sweep& s, double t_end) {
    const V2 end = s.x_at(t_end);
    return {std::min(s.x0.x(), end.x()) - s.bound, std::min(s.x0.y(), end.y()) - s.bound,
            std::max(s.x0.x(), end.x()) + s.bound, std::max(s.x0.y(), end.y()) + s.bound};
}

// Later impacts first out of the heap: std::push_heap keeps the largest on top.
template <class I>
bool later(const I& x, const I& y) {
    if (x.t != y.t) return x.t > y.t;
    return x.a != y.a ? x.a > y.a : x.b > y.b;
}

// Whether two sweeps close faster than `slow` at a point of the bodies' manifold at time t.
bool sweeps_close(const Polygon& a, const Sweep& sa, const Polygon& b, const Sweep& sb, double t,
                  double speculative, double slow) {
    const Transform xa = sa.at(t), xb = sb.at(t);
    const Manifold m = collide(a, xa, b, xb, speculative);
    for (int k = 0; k < m.count; ++k) {
        const V2& p = m.points[k].point;
        const V2 va = sa.v + sa.omega * perp(p - xa.p), vb = sb.v + sb.omega * perp(p - xb.p);
        if (m.normal.dot(vb - va) < -slow) return true;
    }
    return false;
}

// The deepest a pair overlaps at time t, metres (0 when apart).
double depth_at(const Polygon& a, const Sweep& sa, const Polygon& b, const Sweep& sb, double t) {
    const Manifold m = collide(a, sa.at(t), b, sb.at(t), 0);
    double depth = 0;
    for (int k = 0; k < m.count; ++k) depth = std::max(depth, -m.points[k].separation);
    return depth;
}

// For a touching pair that does not close where it touches: the first time it overlaps by
// more than `deep` before t_end, if it does, backed off by bisection to where it overlapped by
// at most `shallow`. The depth is sampled `spacing` of relative travel apart (a thin wall
// could be crossed between samples farther apart), at most 256 times.
std::optional<double> sinks_in(const Polygon& a, const Sweep& sa, const Polygon& b,
                               const Sweep& sb, double t_begin, double t_end, double deep,
                               double shallow, double spacing) {
    if (depth_at(a, sa, b, sb, t_begin) > shallow) return std::nullopt;   // the push-out's
    const double span = t_end - t_begin;
    const double reach = ((sa.v - sb.v).norm() + std::abs(sa.omega) * sa.bound +
                          std::abs(sb.omega) * sb.bound) * span;
    const int samples = static_cast<int>(std::clamp(std::ceil(reach / spacing), 1.0, 256.0));
    double lo = t_begin;
    for (int k = 1; k <= samples; ++k) {
        const double t = k == samples ? t_end : t_begin + span * k / samples;
        if (depth_at(a, sa, b, sb, t) <= deep) {
            lo = t;
            continue;
        }
        double hi = t;
        for (int it = 0; it < 30; ++it) {
            const double mid = 0.5 * (lo + hi);
            (depth_at(a, sa, b, sb, mid) <= shallow ? lo : hi) = mid;
        }
        return lo;
    }
    return std::nullopt;
}

}  // namespace

void BodySolver::predict_impact(const std::vector<Body>& bodies, std::uint32_t i,
                                std::uint32_t j, double t_begin, double dt, bool after_only) {
    const Body& a = bodies[i];
    const Body& b = bodies[j];
    if (a.inv_mass == 0 && b.inv_mass == 0) return;
    if (!fast_[i] && !fast_[j]) return;
    if (apart(std::min(i, j), std::max(i, j))) return;
    if (predictions_left_ == 0) {
        // Out of sweeps: whichever of the two moves stays where its sweep starts.
        if (a.inv_mass > 0) unchecked_[i] = 1;
        if (b.inv_mass > 0) unchecked_[j] = 1;
        return;
    }
    --predictions_left_;
    ++predictions_made_;
    ImpactQuery q;
    q.t_begin = t_begin;
    q.t_end = dt;
    q.target = std::min(impact_gap, 0.01 * std::min(inner_[i], inner_[j]));
    q.tolerance = q.target;
    // Bounding circles do not turn with their bodies: if their centres cannot come within the
    // bounds (plus the target) before the step ends, neither can the surfaces. Most pairs of a
    // falling crowd end here without a distance.
    const Sweep& sa = sweeps_[i];
    const Sweep& sb = sweeps_[j];
    const double centres = (sb.x_at(t_begin) - sa.x_at(t_begin)).norm();
    const double closing = (sb.v - sa.v).norm() * (dt - t_begin);
    if (centres - closing > sa.bound + sb.bound + q.target + q.tolerance) return;
    const TimeOfImpact hit = time_of_impact(shapes_[i], sa, shapes_[j], sb, q);
    if (hit.kind == TimeOfImpact::Kind::apart) return;
    const bool swift = (fast_[i] && !nudged_[i]) || (fast_[j] && !nudged_[j]);
    if (hit.kind == TimeOfImpact::Kind::touching && !swift) return;
    double t = hit.t;
    if (hit.kind == TimeOfImpact::Kind::touching) {
        // Touching already: an impact now if their sweeps close at a point of their manifold
        // (the step's iterations did not stop them, or an impact has just turned one into the
        // other); later, if they slide or turn into each other deeper than the slop by the end.
        if (!sweeps_close(shapes_[i], sa, shapes_[j], sb, t_begin,
                          q.target + q.tolerance, settle_)) {
            const std::optional<double> sink =
                sinks_in(shapes_[i], sa, shapes_[j], sb, t_begin, dt, def_.slop,
                         q.tolerance, 0.25 * std::min(inner_[i], inner_[j]));
            if (!sink) return;
            t = *sink;
        } else if (after_only) {
            return;
        }
    }
    if (after_only && t <= t_begin) return;
    impacts_.push_back({t, hit.gap, i, j, versions_[i], versions_[j]});
    std::push_heap(impacts_.begin(), impacts_.end(), later<PredictedImpact>);
}

void BodySolver::time_impacts(std::vector<Body>& bodies, double dt, double settle) {
    predictions_made_ = 0;
    settle_ = settle;
    const std::size_t fast_count = begin_sweeps(bodies, dt);
    if (fast_count == 0) return;
    list_reach(bodies, dt);
    // The first predictions: only a pair with a fast body can have an impact, so each fast
    // body's swept box is tested against those it reaches, and nothing else (in a tall
    // falling column every box overlaps every other in x). The heap orders the predictions by
    // time and pair, so the order they are made in does not matter.
    impacts_.clear();
    for (std::uint32_t i = 0; i < bodies.size(); ++i) {
        if (!fast_[i]) continue;
        for_each_reachable(i, [&](std::uint32_t j) {
            if (j == i || (fast_[j] && j < i)) return;   // a fast j meets i from its own side
            predict_impact(bodies, std::min(i, j), std::max(i, j), 0, dt);
        });
    }
    std::size_t budget = fast_count * static_cast<std::size_t>(def_.impacts_per_fast_body);
    while (!impacts_.empty() && budget > 0) {
        std::pop_heap(impacts_.begin(), impacts_.end(), later<PredictedImpact>);
        const PredictedImpact e = impacts_.back();
        impacts_.pop_back();
        if (e.version_a != versions_[e.a] || e.version_b != versions_[e.b]) continue;
        --budget;
        take_impact(bodies, e, dt);
    }
    stop_unfinished(bodies);
}

std::size_t BodySolver::begin_sweeps(const std::vector<Body>& bodies, double dt) {
    const std::size_t n = bodies.size();
    sweeps_.resize(n);
    swept_.resize(n);
    std::size_t fast_count = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const Body& b = bodies[i];
        Sweep& s = sweeps_[i];
        s.x0 = start_x_[i];
        s.angle0 = start_angle_[i];
        s.v = (b.x - s.x0) / dt;
        s.omega = (b.angle - s.angle0) / dt;
        s.t0 = 0;
        s.bound = b.radius;
        const double travel = (b.x - s.x0).norm() + std::abs(b.angle - s.angle0) * b.radius;
        if (b.inv_mass > 0 && travel > def_.impact_travel * inner_[i]) fast_[i] = 1;
        fast_count += fast_[i];
    }
    return fast_count;
}

void BodySolver::list_reach(const std::vector<Body>& bodies, double dt) {
    const std::size_t n = bodies.size();
    versions_.assign(n, 0);
    nudged_.assign(n, 0);
    unchecked_.assign(n, 0);
    predictions_left_ = static_cast<std::size_t>(def_.predictions_per_body) * n +
                        static_cast<std::size_t>(def_.predictions_base);
    for (std::size_t i = 0; i < n; ++i) swept_[i] = swept_box(sweeps_[i], dt);
    order_.resize(n);
    for (std::size_t i = 0; i < n; ++i) order_[i] = static_cast<std::uint32_t>(i);
    std::sort(order_.begin(), order_.end(), [&](std::uint32_t i, std::uint32_t j) {
        return swept_[i][0] != swept_[j][0] ? swept_[i][0] < swept_[j][0] : i < j;
    });
    // What a body's new sweep may reach: the bodies that cannot move (walls, held bodies: few,
    // and a container's slabs are wide), the moving ones by their boxes' low x (a box as wide
    // as the widest moving one starting up to that far to the left may overlap), and those an
    // impact has changed since.
    still_.clear();
    moving_.clear();
    widest_ = 0;
    for (const std::uint32_t i : order_) {
        if (bodies[i].inv_mass == 0) {
            still_.push_back(i);
        } else {
            moving_.push_back(i);
            widest_ = std::max(widest_, swept_[i][2] - swept_[i][0]);
        }
    }
    moving_lo_.resize(moving_.size());
    for (std::size_t k = 0; k < moving_.size(); ++k) moving_lo_[k] = swept_[moving_[k]][0];
    changed_.clear();
    changed_flag_.assign(n, 0);
}

template <class F>
void BodySolver::for_each_reachable(std::uint32_t i, F&& f) const {
    const std::array<double, 4>& box = swept_[i];
    for (const std::uint32_t j : still_) {
        if (boxes_overlap(box, swept_[j])) f(j);
    }
    auto from = std::lower_bound(moving_lo_.begin(), moving_lo_.end(), box[0] - widest_);
    for (auto k = static_cast<std::size_t>(from - moving_lo_.begin());
         k < moving_.size() && moving_lo_[k] <= box[2]; ++k) {
        const std::uint32_t j = moving_[k];
        if (!changed_flag_[j] && boxes_overlap(box, swept_[j])) f(j);
    }
    for (const std::uint32_t j : changed_) {
        if (boxes_overlap(box, swept_[j])) f(j);
    }
}

BodySolver::PredictedImpact BodySolver::touching_time(const PredictedImpact& e, double dt) const {
    // Met where the advancement stopped, two bodies leave that gap (up to 0.25 mm) between
    // them for good: two discs head-on ended 0.25 mm further apart than the distance they had
    // flown since they touched. From there they close at their sweeps' speed along the
    // closest points' normal, which a gap this small leaves unchanged to the rounding.
    // Only circles and what is fixed: their surfaces close at that speed however they turn.
    // Polygons keep the gap: carried into touch, a turning corner came in sooner, and a box
    // gas tangled (its median deepest overlap 5 -> 65 % of a half-width; 21 % with only the
    // boxes that did not spin carried).
    const Sweep& sa = sweeps_[e.a];
    const Sweep& sb = sweeps_[e.b];
    const auto steady = [&](std::uint32_t i) {
        return shapes_[i].count == 1 || (sweeps_[i].omega == 0 && sweeps_[i].v == V2::Zero());
    };
    if (e.gap <= 0 || !steady(e.a) || !steady(e.b)) return e;
    const std::optional<Distance> d = distance(shapes_[e.a], sa.at(e.t), shapes_[e.b], sb.at(e.t));
    if (!d || d->distance <= 0) return e;
    BlockContact c;
    c.normal = d->normal;
    BlockPoint p;
    p.ra = d->point - sa.x_at(e.t);
    p.rb = d->point - sb.x_at(e.t);
    const double closing = -normal_velocity(c, p, BlockBody{sa.v, sa.omega, 0, 0},
                                            BlockBody{sb.v, sb.omega, 0, 0});
    if (closing <= 0) return e;
    PredictedImpact at = e;
    at.t = std::min(e.t + d->distance / closing, dt);
    at.gap = 0;
    return at;
}

void BodySolver::take_impact(std::vector<Body>& bodies, const PredictedImpact& predicted,
                             double dt) {
    const PredictedImpact e = touching_time(predicted, dt);
    Body& a = bodies[e.a];
    Body& b = bodies[e.b];
    const Transform xa = sweeps_[e.a].at(e.t), xb = sweeps_[e.b].at(e.t);
    Manifold m = collide(shapes_[e.a], xa, shapes_[e.b], xb, e.gap + 2 * impact_gap);
    if (m.count == 0) {
        // Corner on corner: the reference face's clipping leaves no point. The closest
        // points are the contact.
        const std::optional<Distance> d = distance(shapes_[e.a], xa, shapes_[e.b], xb);
        if (!d) return;
        m.normal = d->normal;
        m.points[0] = {d->point, d->distance, 0};
        m.count = 1;
    }
    BlockContact c;
    c.normal = m.normal;
    c.count = m.count;
    c.friction = def_.mixing.friction_of(a.friction, b.friction);
    BlockBody va = velocity_of(a), vb = velocity_of(b);
    // Closing now, and closing along the sweeps (the motion that brought them here: the
    // step's contacts may have turned them apart only after they had moved into each other).
    const BlockBody sa{sweeps_[e.a].v, sweeps_[e.a].omega, 0, 0};
    const BlockBody sb{sweeps_[e.b].v, sweeps_[e.b].omega, 0, 0};
    bool closing = false, swept_in = false;
    for (int k = 0; k < c.count; ++k) {
        BlockPoint& p = c.points[k];
        p.ra = m.points[k].point - xa.p;
        p.rb = m.points[k].point - xb.p;
        closing = closing || normal_velocity(c, p, va, vb) < -settle_;
        swept_in = swept_in || normal_velocity(c, p, sa, sb) < -settle_;
    }
    if (!closing && !swept_in) {
        // Not meeting where they touch: looked at again only for a later sinking in.
        predict_impact(bodies, e.a, e.b, e.t, dt, true);
        return;
    }
    // Poisson's rule, as a direct island bounces (body_solver.cpp).
    if (closing) collide_poisson(c, va, vb, def_.mixing.restitution_of(a.restitution, b.restitution));

    double impulse = 0;
    for (int k = 0; k < c.count; ++k) impulse += c.points[k].normal_impulse;
    add_impact_touch(e.a, e.b, impulse, true);

    // Each body that the impact moved starts a new sweep from where it was then.
    const std::uint32_t pair[2] = {e.a, e.b};
    const BlockBody* after[2] = {&va, &vb};
    for (int side = 0; side < 2; ++side) {
        const std::uint32_t i = pair[side];
        Body& body = bodies[i];
        if (body.inv_mass == 0) continue;
        Sweep& s = sweeps_[i];
        s.x0 = s.x_at(e.t);
        s.angle0 = s.angle_at(e.t);
        s.t0 = e.t;
        s.v = body.v = after[side]->v;
        s.omega = body.omega = after[side]->omega;
        body.x = s.x_at(dt);
        body.angle = s.angle_at(dt);
        swept_[i] = swept_box(s, dt);
        ++versions_[i];
        // Whatever it now reaches is predicted too. Struck but slow by the measure of the
        // step's start (a pile's body nudged), it is only nudged: what it touches already
        // is left to the next step's contacts rather than struck in turn, which would pass
        // each blow through a pile impact by impact.
        nudged_[i] = (!fast_[i] || nudged_[i]) && !moves_fast(bodies, i, dt);
        fast_[i] = 1;
        if (!changed_flag_[i]) {
            changed_flag_[i] = 1;
            changed_.push_back(i);
        }
    }
    for (int side = 0; side < 2; ++side) {
        const std::uint32_t i = pair[side];
        if (bodies[i].inv_mass == 0) continue;
        for_each_reachable(i, [&](std::uint32_t j) {
            if (j == i || (side == 1 && j == pair[0] && bodies[j].inv_mass > 0)) return;
            predict_impact(bodies, std::min(i, j), std::max(i, j), e.t, dt);
        });
    }
}

void BodySolver::add_impact_touch(std::uint32_t a, std::uint32_t b, double impulse, bool began) {
    const auto touch = std::find_if(impact_touches_.begin(), impact_touches_.end(),
                                    [&](const PairTouch& t) { return t.a == a && t.b == b; });
    if (touch != impact_touches_.end()) {
        touch->impulse += impulse;
    } else if (impulse > 0) {
        impact_touches_.push_back({a, b, impulse, began});
    }
}

void BodySolver::stop_unfinished(std::vector<Body>& bodies) {
    // Out of sweeps: a body whose sweep was not checked against everything it reaches stays
    // where that sweep starts (its last impact, or the step's start), losing the rest of its
    // step; what it would have met, it meets in the next one.
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (!unchecked_[i]) continue;
        Body& body = bodies[i];
        const Sweep& s = sweeps_[i];
        body.x = s.x_at(s.t0);
        body.angle = s.angle_at(s.t0);
        swept_[i] = swept_box(s, s.t0);
        ++versions_[i];
    }
    // Out of impacts: a body still to meet something stops where it would (the rest of its
    // step is lost, as Box2D loses it at every impact), earliest first.
    while (!impacts_.empty()) {
        std::pop_heap(impacts_.begin(), impacts_.end(), later<PredictedImpact>);
        const PredictedImpact e = impacts_.back();
        impacts_.pop_back();
        if (e.version_a != versions_[e.a] || e.version_b != versions_[e.b]) continue;
        for (const std::uint32_t i : {e.a, e.b}) {
            Body& body = bodies[i];
            if (body.inv_mass == 0) continue;
            const Sweep& s = sweeps_[i];
            body.x = s.x_at(e.t);
            body.angle = s.angle_at(e.t);
            ++versions_[i];
        }
    }
}

}  // namespace discreel::physics::detail
