#include "joint.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace discreel::physics::detail {
namespace {

V2 rotated(double angle, const V2& v) {
    const double c = std::cos(angle), s = std::sin(angle);
    return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

// A body's pose and the inverse masses a position correction moves it by (the world's end:
// at the origin, unturned, immovable).
struct Pose {
    V2 x = V2::Zero();
    double angle = 0;
    double inv_mass = 0, inv_inertia = 0;
};

Pose pose_of(const std::vector<Body>& bodies, std::uint32_t i) {
    if (i >= bodies.size()) return {};
    const Body& b = bodies[i];
    return {b.x, b.angle, b.inv_mass, b.inv_inertia};
}

// Impulse p (N s) at the offsets and angular impulse l (N m s) on B, their opposites on A.
void apply(BlockBody& a, BlockBody& b, const V2& ra, const V2& rb, const V2& p, double l) {
    a.v -= a.inv_mass * p;
    a.omega -= a.inv_inertia * (cross(ra, p) + l);
    b.v += b.inv_mass * p;
    b.omega += b.inv_inertia * (cross(rb, p) + l);
}

V2 relative_at(const BlockBody& a, const BlockBody& b, const V2& ra, const V2& rb) {
    return velocity_at(b, rb) - velocity_at(a, ra);
}

// How an impulse at the offsets (x, y) and an angular impulse move the anchors' relative
// velocity and the relative turning: the symmetric 3x3 matrix (11 12 13 22 23 33).
std::array<double, 6> point_matrix(double ma, double ia, const V2& ra, double mb, double ib,
                                   const V2& rb) {
    const double m = ma + mb;
    return {m + ia * ra.y() * ra.y() + ib * rb.y() * rb.y(),
            -ia * ra.x() * ra.y() - ib * rb.x() * rb.y(),
            -ia * ra.y() - ib * rb.y(),
            m + ia * ra.x() * ra.x() + ib * rb.x() * rb.x(),
            ia * ra.x() + ib * rb.x(),
            ia + ib};
}

// x with K x = r for the upper-left 2x2 of k; zero where singular.
V2 solve2(const std::array<double, 6>& k, const V2& r) {
    const double det = k[0] * k[3] - k[1] * k[1];
    if (!(std::abs(det) > 0)) return V2::Zero();
    return {(k[3] * r.x() - k[1] * r.y()) / det, (k[0] * r.y() - k[1] * r.x()) / det};
}

// x with K x = r for the whole 3x3 (Cramer's rule); the 2x2 and no turn where singular (bodies
// that cannot turn).
std::array<double, 3> solve3(const std::array<double, 6>& k, const std::array<double, 3>& r) {
    const double a11 = k[0], a12 = k[1], a13 = k[2], a22 = k[3], a23 = k[4], a33 = k[5];
    const double c11 = a22 * a33 - a23 * a23;
    const double c12 = a13 * a23 - a12 * a33;
    const double c13 = a12 * a23 - a13 * a22;
    const double det = a11 * c11 + a12 * c12 + a13 * c13;
    if (!(std::abs(det) > 1e-15 * (a11 * a22 * a33))) {
        const V2 x = solve2(k, {r[0], r[1]});
        return {x.x(), x.y(), 0};
    }
    const double c22 = a11 * a33 - a13 * a13;
    const double c23 = a12 * a13 - a11 * a23;
    const double c33 = a11 * a22 - a12 * a12;
    return {(c11 * r[0] + c12 * r[1] + c13 * r[2]) / det,
            (c12 * r[0] + c22 * r[1] + c23 * r[2]) / det,
            (c13 * r[0] + c23 * r[1] + c33 * r[2]) / det};
}

double inverse_or_zero(double k) { return k > 0 ? 1 / k : 0; }

}  // namespace

Joints::Joints(std::span<const JointDef> defs, const std::vector<Body>& bodies) {
    held_.assign(bodies.size(), 0);
    for (const JointDef& def : defs) {
        Joint j;
        j.kind = def.kind;
        // An end past the bodies is the world's (the scene loader refuses such a joint).
        const auto end = [&](const std::optional<std::size_t>& i) {
            return i && *i < bodies.size() ? static_cast<std::uint32_t>(*i) : world;
        };
        j.a = end(def.a);
        j.b = end(def.b);
        const Pose a = pose_of(bodies, j.a), b = pose_of(bodies, j.b);
        const bool two_anchors = def.kind == JointDef::Kind::distance;
        const V2 anchor_a = to_v2(def.anchor_a);
        const V2 anchor_b = two_anchors ? to_v2(def.anchor_b) : anchor_a;
        j.local_a = rotated(-a.angle, anchor_a - a.x);
        j.local_b = rotated(-b.angle, anchor_b - b.x);
        const V2 axis = to_v2(def.axis);
        if (axis.norm() > 0) j.axis = rotated(-a.angle, axis.normalized());
        j.reference = b.angle - a.angle;
        j.length = def.length >= 0 ? def.length : (anchor_b - anchor_a).norm();
        j.rope = def.rope;
        j.collide = def.collide;
        if (def.spring) {
            j.spring = true;
            j.frequency = def.spring->frequency;
            j.damping = def.spring->damping;
        }
        if (def.limits) {
            j.limited = true;
            j.lower = (*def.limits)[0];
            j.upper = (*def.limits)[1];
        }
        if (def.motor) {
            j.motor = true;
            j.speed = def.motor->speed;
            j.max_force = def.motor->max_force;
        }
        j.pin = j.kind == JointDef::Kind::revolute && !j.motor && !j.limited;
        narrow_ = narrow_ || !j.pin;
        for (const std::uint32_t i : {j.a, j.b}) {
            if (i != world && i < held_.size()) held_[i] = 1;
        }
        if (j.a != world && j.b != world && !j.collide) {
            const std::uint32_t lo = std::min(j.a, j.b), hi = std::max(j.a, j.b);
            apart_.push_back(std::uint64_t{lo} << 32 | hi);
        }
        joints_.push_back(j);
    }
    std::sort(apart_.begin(), apart_.end());
    for (std::uint32_t i = 0; i < held_.size(); ++i) {
        if (held_[i]) held_list_.push_back(i);
    }
    turn_.assign(held_.size(), {1.0, 0.0});
}

bool Joints::keeps_apart(std::uint32_t i, std::uint32_t j) const {
    return !apart_.empty() &&
           std::binary_search(apart_.begin(), apart_.end(), std::uint64_t{i} << 32 | j);
}

void Joints::turn_all(const std::vector<Body>& bodies) {
    for (const std::uint32_t i : held_list_) {
        if (i < bodies.size()) turn_[i] = {std::cos(bodies[i].angle), std::sin(bodies[i].angle)};
    }
}

void Joints::prepare(const std::vector<Body>& bodies, std::span<BlockBody> state, double dt) {
    turn_all(bodies);
    for (Joint& j : joints_) {
        j.dt = dt;
        prepare_joint(j, bodies, state);
    }
}

void Joints::prepare_joint(Joint& j, const std::vector<Body>& bodies,
                           std::span<BlockBody> state) {
    using Kind = JointDef::Kind;
    const Placed pa = placed(bodies, j.a), pb = placed(bodies, j.b);
    BlockBody& a = at(state, j.a);
    BlockBody& b = at(state, j.b);
    const double ma = a.inv_mass, ia = a.inv_inertia, mb = b.inv_mass, ib = b.inv_inertia;
    j.ra = turned(pa, j.local_a);
    j.rb = turned(pb, j.local_b);
    const V2 d = (pb.x + j.rb) - (pa.x + j.ra);
    const double h = j.dt;
    const double angle = pb.angle - pa.angle - j.reference;
    j.angular_mass = inverse_or_zero(ia + ib);
    j.push = 0;
    j.gamma = j.bias = j.soft_mass = 0;
    // A spring on a row of effective mass `mass` at error c: its push now (explicit) or its
    // soft row (fast springs), and its damping row.
    const auto spring = [&](double mass, double c) {
        const double omega = 2 * std::numbers::pi * j.frequency;
        const double stiffness = mass * omega * omega;
        const double damping = 2 * mass * j.damping * omega;
        const double row_k = inverse_or_zero(mass);
        if (omega * h <= 0.5) {
            j.push = -stiffness * c * h;
            if (damping > 0) j.gamma = 1 / (damping * h);
        } else {
            j.gamma = 1 / (h * (damping + h * stiffness));
            j.bias = c * h * stiffness * j.gamma;
        }
        j.soft_mass = j.gamma > 0 ? 1 / (row_k + j.gamma) : 0;
    };
    switch (j.kind) {
    case Kind::revolute:
        j.k = point_matrix(ma, ia, j.ra, mb, ib, j.rb);
        j.error = angle;
        apply(a, b, j.ra, j.rb, j.linear, j.motor_impulse + j.lower_impulse - j.upper_impulse);
        break;
    case Kind::distance: {
        const double length = d.norm();
        if (length > 1e-12) j.u = d / length;
        j.error = length - j.length;
        const double cra = cross(j.ra, j.u), crb = cross(j.rb, j.u);
        j.mass = inverse_or_zero(ma + mb + ia * cra * cra + ib * crb * crb);
        const bool slack = j.rope && j.error <= 0;
        if (j.spring && !slack) spring(j.mass, j.error);
        if (j.spring && slack) j.along = 0;
        apply(a, b, j.ra, j.rb, (j.along + j.push) * j.u, 0);
        break;
    }
    case Kind::prismatic: {
        // A's row offset is to B's anchor: the axis turns with A about A's centroid.
        j.ra += d;
        j.u = turned(pa, j.axis);
        j.n = perp(j.u);
        j.error = j.u.dot(d);
        const double s1 = cross(j.ra, j.n), s2 = cross(j.rb, j.n);
        const double a1 = cross(j.ra, j.u), a2 = cross(j.rb, j.u);
        j.k = {ma + mb + ia * s1 * s1 + ib * s2 * s2, ia * s1 + ib * s2, 0, ia + ib, 0, 0};
        j.mass = inverse_or_zero(ma + mb + ia * a1 * a1 + ib * a2 * a2);
        const double axial = j.motor_impulse + j.lower_impulse - j.upper_impulse;
        apply(a, b, j.ra, j.rb, j.across * j.n + axial * j.u, j.angular);
        break;
    }
    case Kind::weld:
        j.k = point_matrix(ma, ia, j.ra, mb, ib, j.rb);
        j.error = angle;
        if (j.spring) spring(j.angular_mass, angle);
        apply(a, b, j.ra, j.rb, j.linear, j.angular + j.push);
        break;
    }
}

void Joints::pins(std::vector<PinRef>& out) {
    out.clear();
    for (Joint& j : joints_) {
        if (j.pin) out.push_back({j.a, j.b, j.ra, j.rb, j.k[0], j.k[1], j.k[3], V2::Zero(),
                                  &j.linear});
    }
}

void Joints::solve(std::span<BlockBody> state) {
    for (Joint& j : joints_) {
        if (!j.pin) solve_joint(j, state);
    }
}

template <class Apply>
void Joints::solve_axis(Joint& j, double w, double mass, Apply&& apply_along) {
    if (!(mass > 0)) return;
    if (j.motor) {
        const double limit = j.max_force * j.dt;
        const double before = j.motor_impulse;
        j.motor_impulse = std::clamp(before - mass * (w - j.speed), -limit, limit);
        const double change = j.motor_impulse - before;
        apply_along(change);
        w += change / mass;
    }
    if (!j.limited) return;
    // Apart from a limit, the row lets the bodies close on it within the step (speculative);
    // at or past it, only stop (the position stage corrects).
    {
        const double c = j.error - j.lower;
        const double before = j.lower_impulse;
        j.lower_impulse = std::max(0.0, before - mass * (w + std::max(c, 0.0) / j.dt));
        const double change = j.lower_impulse - before;
        apply_along(change);
        w += change / mass;
    }
    {
        const double c = j.upper - j.error;
        const double before = j.upper_impulse;
        j.upper_impulse = std::max(0.0, before - mass * (-w + std::max(c, 0.0) / j.dt));
        apply_along(-(j.upper_impulse - before));
    }
}

void Joints::solve_joint(Joint& j, std::span<BlockBody> state) {
    using Kind = JointDef::Kind;
    BlockBody& a = at(state, j.a);
    BlockBody& b = at(state, j.b);
    switch (j.kind) {
    case Kind::revolute: {
        solve_axis(j, b.omega - a.omega, j.angular_mass,
                   [&](double l) { apply(a, b, j.ra, j.rb, V2::Zero(), l); });
        const V2 p = -solve2(j.k, relative_at(a, b, j.ra, j.rb));
        j.linear += p;
        apply(a, b, j.ra, j.rb, p, 0);
        break;
    }
    case Kind::distance: {
        const double w = j.u.dot(relative_at(a, b, j.ra, j.rb));
        double change = 0;
        if (j.spring) {
            if (j.soft_mass > 0 && !(j.rope && j.error <= 0)) {
                change = -j.soft_mass * (w + j.bias + j.gamma * j.along);
            }
            j.along += change;
        } else if (j.rope) {
            // Pulls only; slack, it lets the ends close up to the slack within the step.
            const double before = j.along;
            const double slack = std::min(j.error, 0.0) / j.dt;
            j.along = std::min(0.0, before - j.mass * (w + slack));
            change = j.along - before;
        } else {
            change = -j.mass * w;
            j.along += change;
        }
        apply(a, b, j.ra, j.rb, change * j.u, 0);
        break;
    }
    case Kind::prismatic: {
        solve_axis(j, j.u.dot(relative_at(a, b, j.ra, j.rb)), j.mass,
                   [&](double p) { apply(a, b, j.ra, j.rb, p * j.u, 0); });
        const double across = j.n.dot(relative_at(a, b, j.ra, j.rb));
        if (j.k[3] > 0) {
            const V2 x = -solve2({j.k[0], j.k[1], 0, j.k[3], 0, 0}, {across, b.omega - a.omega});
            j.across += x.x();
            j.angular += x.y();
            apply(a, b, j.ra, j.rb, x.x() * j.n, x.y());
        } else if (j.k[0] > 0) {
            const double x = -across / j.k[0];
            j.across += x;
            apply(a, b, j.ra, j.rb, x * j.n, 0);
        }
        break;
    }
    case Kind::weld: {
        if (j.spring) {
            if (j.soft_mass > 0) {
                const double x = -j.soft_mass * (b.omega - a.omega + j.bias + j.gamma * j.angular);
                j.angular += x;
                apply(a, b, j.ra, j.rb, V2::Zero(), x);
            }
            const V2 p = -solve2(j.k, relative_at(a, b, j.ra, j.rb));
            j.linear += p;
            apply(a, b, j.ra, j.rb, p, 0);
            break;
        }
        const V2 v = relative_at(a, b, j.ra, j.rb);
        const auto x = solve3(j.k, {-v.x(), -v.y(), -(b.omega - a.omega)});
        j.linear += V2(x[0], x[1]);
        j.angular += x[2];
        apply(a, b, j.ra, j.rb, V2(x[0], x[1]), x[2]);
        break;
    }
    }
}

double Joints::correct(std::vector<Body>& bodies, std::span<Moved> moved) {
    turn_all(bodies);
    double worst = 0;
    for (const Joint& j : joints_) {
        if (!j.pin) worst = std::max(worst, correct_joint(j, bodies, moved));
    }
    return worst;
}

double Joints::pin_gaps(const std::vector<Body>& bodies, std::vector<PinRef>& out) {
    out.clear();
    turn_all(bodies);
    double widest = 0;
    for (Joint& j : joints_) {
        if (!j.pin) continue;
        const Placed pa = placed(bodies, j.a), pb = placed(bodies, j.b);
        const V2 ra = turned(pa, j.local_a), rb = turned(pb, j.local_b);
        const V2 d = (pb.x + rb) - (pa.x + ra);
        const double gap = d.norm();
        widest = std::max(widest, gap);
        // Every pin, closed or not: one left out would open freely as its bodies move.
        const auto k = point_matrix(pa.inv_mass, pa.inv_inertia, ra, pb.inv_mass,
                                    pb.inv_inertia, rb);
        // As the one-by-one pass: at most max_shift at a time (a pin pulled far apart is
        // brought back over steps, not flung).
        const V2 step = gap > max_shift ? V2(d * (max_shift / gap)) : d;
        out.push_back({j.a, j.b, ra, rb, k[0], k[1], k[3], -step, nullptr});
    }
    return widest;
}

Joints::Placed Joints::placed(const std::vector<Body>& bodies, std::uint32_t i) const {
    if (i >= bodies.size()) return {};
    const Body& b = bodies[i];
    return {b.x, b.angle, turn_[i].first, turn_[i].second, b.inv_mass, b.inv_inertia};
}

void Joints::move(std::vector<Body>& bodies, std::span<Moved> moved, std::uint32_t i,
                  const V2& by, double turn) {
    bodies[i].x += by;
    bodies[i].angle += turn;
    moved[i].by += by;
    moved[i].turn += turn;
    turn_[i] = turned_on(turn_[i], turn);
}

double Joints::correct_joint(const Joint& j, std::vector<Body>& bodies, std::span<Moved> moved) {
    using Kind = JointDef::Kind;
    const Placed pa = placed(bodies, j.a), pb = placed(bodies, j.b);
    const double ma = pa.inv_mass, ia = pa.inv_inertia, mb = pb.inv_mass, ib = pb.inv_inertia;
    if (ma + mb + ia + ib <= 0) return 0;
    V2 ra = turned(pa, j.local_a);
    const V2 rb = turned(pb, j.local_b);
    // A pass corrects at most max_shift metres and max_turn radians (Box2D's 0.2 m and 8
    // degrees): a joint far from its geometry (a limit the start lies beyond) is brought back
    // over steps, not flung there in one.
    // The errors' sizes are returned whole, so the passes go on while they are large.
    const V2 d = (pb.x + rb) - (pa.x + ra);
    const double turn = pb.angle - pa.angle - j.reference;
    const V2 d_step = d.norm() > max_shift ? V2(d * (max_shift / d.norm())) : d;
    const double turn_step = std::clamp(turn, -max_turn, max_turn);
    // A positional impulse p (kg m) at the offsets and an angular one l (kg m^2 rad).
    const auto shift = [&](const V2& at_a, const V2& p, double l) {
        if (j.a != world && (ma > 0 || ia > 0)) {
            move(bodies, moved, j.a, -ma * p, -ia * (cross(at_a, p) + l));
        }
        if (j.b != world && (mb > 0 || ib > 0)) {
            move(bodies, moved, j.b, mb * p, ib * (cross(rb, p) + l));
        }
    };
    // A limit of an angle or a travel along u (u zero: an angle), pushed back within it.
    const auto limit = [&](double value, double mass, const V2& at_a, const V2& u) {
        if (!j.limited || !(mass > 0)) return 0.0;
        const double c = std::clamp(
            value < j.lower ? value - j.lower : value > j.upper ? value - j.upper : 0.0,
            u == V2::Zero() ? -max_turn : -max_shift, u == V2::Zero() ? max_turn : max_shift);
        if (std::abs(c) <= tolerance) return std::abs(c);
        const double x = -mass * c;
        shift(at_a, x * u, u == V2::Zero() ? x : 0);
        return std::abs(c);
    };
    switch (j.kind) {
    case Kind::revolute: {
        const double off = limit(turn, inverse_or_zero(ia + ib), ra, V2::Zero());
        if (d.norm() <= tolerance) return off;
        const auto k = point_matrix(ma, ia, ra, mb, ib, rb);
        shift(ra, -solve2(k, d_step), 0);
        return std::max(off, d.norm());
    }
    case Kind::distance: {
        const double length = d.norm();
        const double c = length - j.length;
        if (j.spring || (j.rope && c <= 0) || std::abs(c) <= tolerance || length <= 1e-12) {
            return j.spring || j.rope ? 0 : std::abs(c);
        }
        const V2 u = d / length;
        const double cra = cross(ra, u), crb = cross(rb, u);
        const double mass = inverse_or_zero(ma + mb + ia * cra * cra + ib * crb * crb);
        shift(ra, -mass * std::clamp(c, -max_shift, max_shift) * u, 0);
        return std::abs(c);
    }
    case Kind::prismatic: {
        ra += d;
        const V2 u = turned(pa, j.axis), n = perp(u);
        const double a1 = cross(ra, u), a2 = cross(rb, u);
        const double off =
            limit(u.dot(d), inverse_or_zero(ma + mb + ia * a1 * a1 + ib * a2 * a2), ra, u);
        const double across = n.dot(d);
        if (std::abs(across) <= tolerance && std::abs(turn) <= tolerance) return off;
        const double s1 = cross(ra, n), s2 = cross(rb, n);
        const std::array<double, 6> k{ma + mb + ia * s1 * s1 + ib * s2 * s2, ia * s1 + ib * s2, 0,
                                      ia + ib, 0, 0};
        const double across_step = std::clamp(across, -max_shift, max_shift);
        if (k[3] > 0) {
            const V2 x = -solve2(k, {across_step, turn_step});
            shift(ra, x.x() * n, x.y());
        } else if (k[0] > 0) {
            shift(ra, -across_step / k[0] * n, 0);
        }
        return std::max({off, std::abs(across), std::abs(turn)});
    }
    case Kind::weld: {
        const auto k = point_matrix(ma, ia, ra, mb, ib, rb);
        if (j.spring) {
            if (d.norm() <= tolerance) return 0;
            shift(ra, -solve2(k, d_step), 0);
            return d.norm();
        }
        if (d.norm() <= tolerance && std::abs(turn) <= tolerance) return 0;
        const auto x = solve3(k, {-d_step.x(), -d_step.y(), -turn_step});
        shift(ra, V2(x[0], x[1]), x[2]);
        return std::max(d.norm(), std::abs(turn));
    }
    }
    return 0;
}

void Joints::states(const std::vector<Body>& bodies, std::vector<JointState>& out) const {
    using Kind = JointDef::Kind;
    out.resize(joints_.size());
    for (std::size_t i = 0; i < joints_.size(); ++i) {
        const Joint& j = joints_[i];
        const Pose pa = pose_of(bodies, j.a), pb = pose_of(bodies, j.b);
        const V2 anchor_a = pa.x + rotated(pa.angle, j.local_a);
        const V2 anchor_b = pb.x + rotated(pb.angle, j.local_b);
        V2 impulse = j.linear;
        double angular = 0;
        switch (j.kind) {
        case Kind::revolute:
            angular = j.motor_impulse + j.lower_impulse - j.upper_impulse;
            break;
        case Kind::distance:
            impulse = (j.along + j.push) * j.u;
            break;
        case Kind::prismatic:
            impulse = j.across * j.n + (j.motor_impulse + j.lower_impulse - j.upper_impulse) * j.u;
            angular = j.angular;
            break;
        case Kind::weld:
            angular = j.angular + j.push;
            break;
        }
        const double per_second = j.dt > 0 ? 1 / j.dt : 0;
        JointState& s = out[i];
        s.anchor_a = {anchor_a.x(), anchor_a.y()};
        s.anchor_b = {anchor_b.x(), anchor_b.y()};
        s.force = {impulse.x() * per_second, impulse.y() * per_second};
        s.torque = angular * per_second;
    }
}

}  // namespace discreel::physics::detail
