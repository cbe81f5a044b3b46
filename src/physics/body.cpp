#include "body.hpp"

#include "discreel/shapes.hpp"

namespace discreel::physics::detail {

Body make_body(const BodyDef& def) {
    Body b;
    b.x = to_v2(def.position);
    b.angle = def.angle;
    b.radius = def.shape ? physics::bounding_radius(*def.shape) : def.radius;
    b.restitution = def.restitution;
    b.friction = def.friction;
    if (def.is_static) {
        b.motion = Motion::fixed;
        return b;
    }
    b.motion = Motion::dynamic;
    b.v = to_v2(def.velocity);
    b.omega = def.angular_velocity;
    b.mass = def.mass;
    b.inertia = inertia_of(def);
    b.inv_mass = 1.0 / b.mass;
    b.inv_inertia = b.inertia > 0 ? 1.0 / b.inertia : 0.0;
    return b;
}

void add_energy(std::span<const Body> bodies, const V2& gravity, WorldStats& stats) {
    for (const Body& b : bodies) {
        if (b.motion == Motion::fixed) continue;
        stats.kinetic_energy +=
            0.5 * b.mass * b.v.squaredNorm() + 0.5 * b.inertia * b.omega * b.omega;
        stats.potential_energy -= b.mass * gravity.dot(b.x);
    }
}

}  // namespace discreel::physics::detail
