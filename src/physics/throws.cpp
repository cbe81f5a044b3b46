#include "throws.hpp"

namespace discreel::physics::detail {
namespace {

V2 path_at(const std::vector<Waypoint>& path, double t) {
    if (t <= path.front().t) return to_v2(path.front().position);
    for (std::size_t k = 1; k < path.size(); ++k) {
        const Waypoint& p0 = path[k - 1];
        const Waypoint& p1 = path[k];
        if (t < p1.t) {
            const double s = (t - p0.t) / (p1.t - p0.t);
            return to_v2(p0.position) + (to_v2(p1.position) - to_v2(p0.position)) * s;
        }
    }
    return to_v2(path.back().position);
}

V2 final_velocity(const std::vector<Waypoint>& path) {
    if (path.size() < 2) return V2::Zero();
    const Waypoint& p0 = path[path.size() - 2];
    const Waypoint& p1 = path.back();
    if (p1.t <= p0.t) return V2::Zero();
    return (to_v2(p1.position) - to_v2(p0.position)) / (p1.t - p0.t);
}

void release(Body& b, const V2& v) {
    b.motion = Motion::dynamic;
    b.inv_mass = 1.0 / b.mass;
    b.inv_inertia = 1.0 / b.inertia;
    b.v = v;
}

}  // namespace

Throws::Throws(const std::vector<ThrowDef>& defs) {
    for (const ThrowDef& d : defs) throws_.push_back(Throw{d, Stage::waiting});
}

void Throws::start(std::vector<Body>& bodies) {
    for (Throw& th : throws_) {
        std::vector<Waypoint>& path = th.def.path;
        Body& b = bodies[th.def.body];
        if (path.empty() || b.motion == Motion::fixed) continue;
        if (path.front().t > 0) path.insert(path.begin(), Waypoint{0.0, Vec2{b.x.x(), b.x.y()}});
        b.x = to_v2(path.front().position);
        b.v = V2::Zero();
        b.hold();
        th.stage = Stage::holding;
    }
}

bool Throws::begin_step(double t0, double t1, std::vector<Body>& bodies) {
    bool changed = false;
    for (Throw& th : throws_) {
        if (th.stage == Stage::done) continue;
        Body& b = bodies[th.def.body];
        if (b.motion == Motion::fixed) {
            th.stage = Stage::done;
            continue;
        }
        const std::vector<Waypoint>& path = th.def.path;
        if (path.empty()) {
            if (t0 < th.def.at) continue;
            if (th.def.velocity) b.v = to_v2(*th.def.velocity);
            changed = true;
            th.stage = Stage::done;
            continue;
        }
        if (t0 >= path.back().t) {
            b.x = to_v2(path.back().position);
            release(b, th.def.release ? to_v2(*th.def.release) : final_velocity(path));
            changed = true;   // its mass is back: the solver's masses of its contacts change
            th.stage = Stage::done;
            continue;
        }
        b.x = path_at(path, t0);
        b.v = (path_at(path, t1) - b.x) / (t1 - t0);
        changed = true;
    }
    return changed;
}

void Throws::end_step(double t1, std::vector<Body>& bodies) const {
    for (const Throw& th : throws_) {
        if (th.stage != Stage::holding) continue;
        bodies[th.def.body].x = path_at(th.def.path, t1);
    }
}

}  // namespace discreel::physics::detail
