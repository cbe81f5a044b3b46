#include "shape_world.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace discreel::physics::detail {
namespace {

V2 to_v2(const Vec2& p) { return V2(p.x, p.y); }

Polygon shape_of(const BodyDef& d) { return d.shape ? to_polygon(*d.shape) : make_circle(d.radius); }

Body make_fixed(const Polygon& shape, const V2& at, double angle, const WallDef& w) {
    Body b;
    b.x = at;
    b.radius = bounding_radius(shape);
    b.angle = angle;
    b.restitution = w.restitution;
    b.friction = w.friction;
    b.motion = Motion::fixed;
    return b;
}

BodySolverDef solver_def(const WorldDef& def) {
    BodySolverDef s;
    if (def.iterations != 0) s.iterations = std::max(1, def.iterations);
    s.sleep = def.sleep;
    return s;
}

}  // namespace

bool ShapeWorld::wanted(const WorldDef& def) {
    const auto shaped = [](const BodyDef& d) { return d.shape.has_value(); };
    return uses_manifold_solver(std::any_of(def.bodies.begin(), def.bodies.end(), shaped),
                                !def.respawns.empty());
}

ShapeWorld::ShapeWorld(const WorldDef& def, int substeps)
    : gravity_(to_v2(def.gravity)),
      substeps_(substeps),
      body_count_(def.bodies.size()),
      solver_(solver_def(def)),
      throws_(def.throws),
      respawns_(def.respawns) {
    for (const BodyDef& d : def.bodies) {
        bodies_.push_back(make_body(d));
        shapes_.push_back(shape_of(d));
    }
    for (std::size_t i = 0; i < def.walls.size(); ++i) {
        const WallDef& w = def.walls[i];
        if (w.shape == WallDef::Shape::box) {
            const V2 lo(std::min(w.a.x, w.b.x), std::min(w.a.y, w.b.y));
            const V2 hi(std::max(w.a.x, w.b.x), std::max(w.a.y, w.b.y));
            for (const Slab& s : container_slabs(lo, hi)) {
                bodies_.push_back(make_fixed(s.shape, s.centre, 0, w));
                shapes_.push_back(s.shape);
                wall_of_.push_back(i);
            }
            continue;
        }
        const V2 a = to_v2(w.a), b = to_v2(w.b);
        const double length = (b - a).norm();
        const auto capsule = make_capsule(length, 0.5 * w.thickness);
        const Polygon shape = capsule ? *capsule : make_circle(0.5 * w.thickness);
        bodies_.push_back(make_fixed(shape, 0.5 * (a + b), std::atan2(b.y() - a.y(), b.x() - a.x()), w));
        shapes_.push_back(shape);
        wall_of_.push_back(i);
    }
    throws_.start(bodies_);
    states_.resize(body_count_);
}

void ShapeWorld::respawn(double t0) {
    while (respawns_applied_ < respawns_.size() && respawns_[respawns_applied_].at <= t0) {
        const RespawnDef& r = respawns_[respawns_applied_++];
        const std::size_t last = std::min(body_count_, r.first + r.bodies.size());
        solver_.forget(bodies_, r.first, last);
        for (std::size_t i = r.first; i < last; ++i) {
            Body fresh = make_body(r.bodies[i - r.first]);
            shapes_[i] = shape_of(r.bodies[i - r.first]);
            // A held body stays held: its throw still owns it.
            if (bodies_[i].motion == Motion::held) {
                fresh.x = bodies_[i].x;
                fresh.v = bodies_[i].v;
                fresh.motion = Motion::held;
                fresh.inv_mass = 0;
                fresh.inv_inertia = 0;
            }
            bodies_[i] = fresh;
        }
    }
}

void ShapeWorld::step(double t0, double t1) {
    respawn(t0);
    throws_.begin_step(t0, t1, bodies_);
    const double h = (t1 - t0) / substeps_;
    for (int k = 0; k < substeps_; ++k) {
        solver_.step(bodies_, shapes_, gravity_, h);
        for (const PairTouch& touch : solver_.touches()) {
            if (!touch.began) continue;
            ContactEvent e;
            e.t = t1;
            e.a = touch.a;
            if (touch.b >= body_count_) {
                e.other_kind = ContactEvent::Other::wall;
                e.other = wall_of_[touch.b - body_count_];
            } else {
                e.other_kind = ContactEvent::Other::body;
                e.other = touch.b;
            }
            e.impulse = touch.impulse;
            events_.push_back(e);
        }
        touching_ = solver_.touching();
    }
    throws_.end_step(t1, bodies_);
}

std::span<const BodyState> ShapeWorld::states() const {
    for (std::size_t i = 0; i < body_count_; ++i) states_[i] = state_of(bodies_[i]);
    return states_;
}

std::optional<std::size_t> ShapeWorld::non_finite() const {
    for (std::size_t i = 0; i < body_count_; ++i) {
        const Body& b = bodies_[i];
        if (!std::isfinite(b.x.x() + b.x.y() + b.v.x() + b.v.y() + b.angle + b.omega)) return i;
    }
    return std::nullopt;
}

WorldStats ShapeWorld::stats(const V2& gravity) const {
    WorldStats s;
    add_energy(std::span(bodies_).first(body_count_), gravity, s);
    const BodySolver::Overlap o = solver_.max_overlap(bodies_, shapes_);
    s.max_overlap = o.depth;
    if (o.depth > 0) {
        const double a = bodies_[o.a].radius;
        const double b = o.b < body_count_ ? bodies_[o.b].radius : a;
        s.max_overlap_ratio = o.depth / std::min(a, b);
    }
    s.contact_count = touching_;
    s.sweeps = solver_.sweeps();
    return s;
}

}  // namespace discreel::physics::detail
