#include "shape_stepper.hpp"

#include <algorithm>
#include <cmath>

namespace discreel::physics::detail {
namespace {

Polygon shape_of(const BodyDef& d) {
    return d.shape ? to_polygon(*d.shape) : make_circle(d.radius);
}

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
    s.mixing = def.mixing;
    return s;
}

}  // namespace

ShapeStepper::ShapeStepper(const WorldDef& def, int substeps, std::vector<Body>& bodies)
    : gravity_(to_v2(def.gravity)),
      substeps_(substeps),
      body_count_(def.bodies.size()),
      solver_(solver_def(def)) {
    for (const BodyDef& d : def.bodies) shapes_.push_back(shape_of(d));
    const auto add = [&](const Polygon& shape, const V2& at, double angle, std::size_t wall) {
        bodies.push_back(make_fixed(shape, at, angle, def.walls[wall]));
        shapes_.push_back(shape);
        wall_of_.push_back(wall);
    };
    for (std::size_t i = 0; i < def.walls.size(); ++i) {
        const WallDef& w = def.walls[i];
        if (w.shape == WallDef::Shape::box) {
            const V2 lo(std::min(w.a.x, w.b.x), std::min(w.a.y, w.b.y));
            const V2 hi(std::max(w.a.x, w.b.x), std::max(w.a.y, w.b.y));
            for (const Slab& s : container_slabs(lo, hi)) add(s.shape, s.centre, 0, i);
            continue;
        }
        const V2 a = to_v2(w.a), b = to_v2(w.b);
        const double length = (b - a).norm();
        const auto capsule = make_capsule(length, 0.5 * w.thickness);
        const Polygon shape = capsule ? *capsule : make_circle(0.5 * w.thickness);
        add(shape, 0.5 * (a + b), std::atan2(b.y() - a.y(), b.x() - a.x()), i);
    }
    solver_.set_joints(Joints(def.joints, bodies));
    for (std::size_t i = 0; i < def.bodies.size(); ++i) {
        const BodyDef& d = def.bodies[i];
        solver_.filter().set(static_cast<std::uint32_t>(i), d.category, d.collides, d.sensor);
    }
    for (std::size_t k = 0; k < wall_of_.size(); ++k) {
        const WallDef& w = def.walls[wall_of_[k]];
        solver_.filter().set(static_cast<std::uint32_t>(body_count_ + k), w.category, w.collides,
                             false);
    }
}

void ShapeStepper::replaced(std::size_t i, const BodyDef& def) {
    shapes_[i] = shape_of(def);
    solver_.filter().set(static_cast<std::uint32_t>(i), def.category, def.collides, def.sensor);
}

void ShapeStepper::step(std::vector<Body>& bodies, double t0, double t1, bool thrown,
                        std::vector<PairTouch>& began) {
    // A throw's changes need only end the keeping of contacts (a release gives a held body
    // back its mass: pairs with walls it did not have); otherwise each substep looks at every
    // body's motion afresh. The substeps divide t1 - t0, which differs from 1 / rate by
    // rounding (the disc solver's divide 1 / rate): either is deterministic, and each
    // solver's pinned hashes hold.
    if (thrown) solver_.thrown();
    const double h = (t1 - t0) / substeps_;
    for (int k = 0; k < substeps_; ++k) {
        solver_.step(bodies, shapes_, gravity_, h);
        for (const PairTouch& touch : solver_.touches()) {
            if (touch.began) began.push_back(touch);
        }
        began.insert(began.end(), solver_.sensed().begin(), solver_.sensed().end());
        touching_ = solver_.touching();
    }
}

std::optional<std::size_t> ShapeStepper::end_step(std::vector<Body>& bodies, double /*dt*/) {
    for (std::size_t i = 0; i < body_count_; ++i) {
        const Body& b = bodies[i];
        if (!std::isfinite(b.x.x() + b.x.y() + b.v.x() + b.v.y() + b.angle + b.omega)) return i;
    }
    return std::nullopt;
}

void ShapeStepper::add_stats(const std::vector<Body>& bodies, std::size_t body_count,
                             WorldStats& stats) const {
    const BodySolver::Overlap o = solver_.max_overlap(bodies, shapes_);
    stats.max_overlap = o.depth;
    if (o.depth > 0) {
        const double a = bodies[o.a].radius;
        const double b = o.b < body_count ? bodies[o.b].radius : a;
        stats.max_overlap_ratio = o.depth / std::min(a, b);
    }
    stats.contact_count = touching_;
    stats.sweeps = solver_.sweeps();
}

}  // namespace discreel::physics::detail
