#include "build_world.hpp"

namespace discreel::job {

namespace {

physics::BodyDef body_of(const scene::Body& d) {
    physics::BodyDef disc;
    disc.position = d.position;
    disc.velocity = d.velocity;
    disc.angle = d.angle;
    disc.angular_velocity = d.angular_velocity;
    disc.radius = d.radius;
    disc.mass = d.mass;
    disc.restitution = d.restitution;
    disc.friction = d.friction;
    disc.is_static = d.is_static;
    disc.shape = d.shape;
    disc.kinematic = d.kinematic;
    disc.category = d.category;
    disc.collides = d.collides;
    disc.sensor = d.sensor;
    return disc;
}

}  // namespace

physics::WorldDef build_world(const scene::Scene& scene) {
    physics::WorldDef def;
    def.gravity = scene.physics.gravity;
    def.rate = scene.physics.rate;
    def.substeps = scene.physics.substeps;
    def.iterations = scene.physics.iterations;
    def.sleep = scene.physics.sleep;
    def.mixing = scene.physics.mix;
    def.bodies.reserve(scene.bodies.size());
    for (const scene::Body& d : scene.bodies) def.bodies.push_back(body_of(d));
    for (const scene::Respawn& r : scene.respawns) {
        physics::RespawnDef respawn;
        respawn.at = r.at;
        respawn.first = r.first;
        for (const scene::Body& d : r.bodies) respawn.bodies.push_back(body_of(d));
        def.respawns.push_back(std::move(respawn));
    }
    def.walls.reserve(scene.walls.size());
    for (const scene::Wall& w : scene.walls) {
        physics::WallDef wall;
        wall.shape = w.shape == scene::Wall::Shape::box ? physics::WallDef::Shape::box
                                                        : physics::WallDef::Shape::segment;
        wall.a = w.a;
        wall.b = w.b;
        wall.thickness = w.thickness;
        wall.restitution = w.restitution;
        wall.friction = w.friction;
        wall.category = w.category;
        wall.collides = w.collides;
        def.walls.push_back(wall);
    }
    def.joints = scene.joints;
    def.throws.reserve(scene.throws.size());
    for (const scene::Throw& t : scene.throws) {
        physics::ThrowDef th;
        th.body = t.body;
        th.at = t.at;
        th.velocity = t.velocity;
        th.release = t.release;
        for (const scene::Waypoint& p : t.path) th.path.push_back({p.t, p.position});
        def.throws.push_back(th);
    }
    return def;
}

}  // namespace discreel::job
