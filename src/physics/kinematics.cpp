#include "kinematics.hpp"

#include <algorithm>
#include <cmath>

namespace discreel::physics::detail {

Kinematics::Kinematics(const std::vector<BodyDef>& bodies) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const BodyDef& d = bodies[i];
        if (!d.kinematic || d.is_static) continue;
        Moving m{i, *d.kinematic, to_v2(d.position), d.angle};
        std::vector<KinematicDef::Pose>& path = m.def.path;
        if (!path.empty() && path.front().t > 0) {
            path.insert(path.begin(), KinematicDef::Pose{0.0, d.position, d.angle});
        }
        moving_.push_back(std::move(m));
    }
}

Kinematics::Pose Kinematics::pose_at(const Moving& m, double t) {
    const std::vector<KinematicDef::Pose>& path = m.def.path;
    if (path.empty()) {
        return {m.start + to_v2(m.def.velocity) * t, m.start_angle + m.def.angular_velocity * t};
    }
    const double end = path.back().t;
    if (t >= end) {
        // A looping path starts again from its beginning (t = 0, where the body started or
        // its first pose); a path of one pose, or none after its end, stays put.
        if (!m.def.loop || !(end > 0)) return {to_v2(path.back().position), path.back().angle};
        t = std::fmod(t, end);
    }
    // The first pose after t (the path's times increase strictly).
    const auto next = std::upper_bound(path.begin(), path.end(), t,
                                       [](double v, const KinematicDef::Pose& p) { return v < p.t; });
    if (next == path.begin()) return {to_v2(path.front().position), path.front().angle};
    if (next == path.end()) return {to_v2(path.back().position), path.back().angle};
    const KinematicDef::Pose& p0 = *(next - 1);
    const KinematicDef::Pose& p1 = *next;
    const double s = (t - p0.t) / (p1.t - p0.t);
    return {to_v2(p0.position) + (to_v2(p1.position) - to_v2(p0.position)) * s,
            p0.angle + (p1.angle - p0.angle) * s};
}

void Kinematics::start(std::vector<Body>& bodies) const {
    for (const Moving& m : moving_) {
        Body& b = bodies[m.body];
        const Pose p = pose_at(m, 0);
        b.x = p.x;
        b.angle = p.angle;
        b.v = V2::Zero();
        b.hold();
    }
}

bool Kinematics::begin_step(double t0, double t1, std::vector<Body>& bodies) {
    bool changed = jumped_;
    jumped_ = false;
    for (const Moving& m : moving_) {
        Body& b = bodies[m.body];
        const Pose from = pose_at(m, t0);
        Pose to = pose_at(m, t1);
        // A looping path that starts its next lap within the step jumps back (unless it ends
        // where it begins): the body moves on along the lap it is in, at that lap's last
        // velocity, and is put at the new lap's pose at the step's end. Its chord would be
        // the jump over one step: metres in 2 ms, pushing whatever it crosses.
        const double end = m.def.path.empty() ? 0.0 : m.def.path.back().t;
        if (m.def.loop && end > 0 && std::floor(t0 / end) != std::floor(t1 / end)) {
            const double last = std::nextafter(end, 0.0);
            const Pose before = pose_at(m, last - (t1 - t0));
            const Pose at_end = pose_at(m, last);
            to = {from.x + (at_end.x - before.x), from.angle + (at_end.angle - before.angle)};
            jumped_ = true;
        }
        const V2 v = (to.x - from.x) / (t1 - t0);
        const double omega = (to.angle - from.angle) / (t1 - t0);
        changed = changed || v != b.v || omega != b.omega;
        b.x = from.x;
        b.angle = from.angle;
        b.v = v;
        b.omega = omega;
    }
    return changed;
}

void Kinematics::end_step(double t1, std::vector<Body>& bodies) const {
    for (const Moving& m : moving_) {
        const Pose p = pose_at(m, t1);
        bodies[m.body].x = p.x;
        bodies[m.body].angle = p.angle;
    }
}

}  // namespace discreel::physics::detail
