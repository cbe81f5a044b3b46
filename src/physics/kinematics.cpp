#include "kinematics.hpp"

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
    for (std::size_t k = 1; k < path.size(); ++k) {
        const KinematicDef::Pose& p0 = path[k - 1];
        const KinematicDef::Pose& p1 = path[k];
        if (t >= p1.t) continue;
        const double s = t <= p0.t ? 0.0 : (t - p0.t) / (p1.t - p0.t);
        return {to_v2(p0.position) + (to_v2(p1.position) - to_v2(p0.position)) * s,
                p0.angle + (p1.angle - p0.angle) * s};
    }
    return {to_v2(path.back().position), path.back().angle};
}

void Kinematics::start(std::vector<Body>& bodies) const {
    for (const Moving& m : moving_) {
        Body& b = bodies[m.body];
        const Pose p = pose_at(m, 0);
        b.x = p.x;
        b.angle = p.angle;
        b.v = V2::Zero();
        b.omega = 0;
        b.motion = Motion::held;
        b.inv_mass = 0;
        b.inv_inertia = 0;
    }
}

void Kinematics::begin_step(double t0, double t1, std::vector<Body>& bodies) const {
    for (const Moving& m : moving_) {
        Body& b = bodies[m.body];
        const Pose from = pose_at(m, t0), to = pose_at(m, t1);
        b.x = from.x;
        b.angle = from.angle;
        b.v = (to.x - from.x) / (t1 - t0);
        b.omega = (to.angle - from.angle) / (t1 - t0);
    }
}

void Kinematics::end_step(double t1, std::vector<Body>& bodies) const {
    for (const Moving& m : moving_) {
        const Pose p = pose_at(m, t1);
        bodies[m.body].x = p.x;
        bodies[m.body].angle = p.angle;
    }
}

}  // namespace discreel::physics::detail
