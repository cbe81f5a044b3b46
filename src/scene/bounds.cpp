// Numbers no scene needs, refused at the value that carries them (scene::ranges): a mass of
// 1e-300 kg or 1e15 kg, gravity of 1e6 m/s^2, a spin of 1e8 rad/s or a speed of 1e9 m/s is a
// typo, and the physics cannot keep such a body inside its walls.
#include <cmath>
#include <string>

#include "loader.hpp"

namespace discreel::scene::detail {
namespace {

double length(Vec2 v) { return std::hypot(v.x, v.y); }

}  // namespace

std::string format_bound(double value) {
    std::string text = format_short(value);
    const auto e = text.find('e');
    if (e == std::string::npos) return text;
    std::string exponent = text.substr(e + 1);
    const bool negative = exponent.front() == '-';
    if (exponent.front() == '+' || negative) exponent.erase(0, 1);
    exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
    return text.substr(0, e + 1) + (negative ? "-" : "") + exponent;
}

namespace {

std::string number(double value) { return format_bound(value); }

// One message per entry: a generator's bodies share their entry, and its first offender
// speaks for all.
class Once {
public:
    bool first(const Location& where) {
        if (said_ && where.line == last_.line && where.column == last_.column) return false;
        said_ = true;
        last_ = where;
        return true;
    }

private:
    bool said_ = false;
    Location last_{};
};

void check_body(const Body& body, const BodySource& source, Diagnostics& d, Once& mass_once,
                Once& speed_once, Once& spin_once) {
    // A body whose entry failed to read (its mass unset) has its problem reported already.
    if (body.is_static || !source.usable || !(body.mass > 0) || !std::isfinite(body.mass)) return;
    if ((body.mass < ranges.min_mass || body.mass > ranges.max_mass) &&
        mass_once.first(source.entry)) {
        d.error(source.entry, source.where + ": a mass of " + number(body.mass) +
                                  " kg is outside the masses discreel simulates, " +
                                  number(ranges.min_mass) + " to " +
                                  number(ranges.max_mass) + " kg");
    }
    if (length(body.velocity) > ranges.max_speed && speed_once.first(source.velocity_where)) {
        d.error(source.velocity_where,
                source.velocity_path + ": a speed of " + number(length(body.velocity)) +
                    " m/s is beyond any scene's; speeds are at most " +
                    number(ranges.max_speed) + " m/s");
    }
    if (std::abs(body.angular_velocity) > ranges.max_spin && spin_once.first(source.entry)) {
        d.error(source.entry, source.where + ": a spin of " +
                                  number(std::abs(body.angular_velocity)) +
                                  " rad/s is beyond any scene's; spins are at most " +
                                  number(ranges.max_spin) + " rad/s");
    }
}

void check_speed(double speed, const Location& where, const std::string& path, Diagnostics& d) {
    if (speed <= ranges.max_speed) return;
    d.error(where, path + ": a speed of " + number(speed) +
                       " m/s is beyond any scene's; speeds are at most " +
                       number(ranges.max_speed) + " m/s");
}

}  // namespace

void check_ranges(Loader& loader) {
    Diagnostics& d = loader.diagnostics;
    const Scene& scene = loader.scene;
    if (loader.sources.size() != scene.bodies.size()) return;
    Once mass_once, speed_once, spin_once;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        check_body(scene.bodies[i], loader.sources[i], d, mass_once, speed_once, spin_once);
    }
    for (const Respawn& respawn : scene.respawns) {
        for (std::size_t k = 0; k < respawn.bodies.size(); ++k) {
            if (respawn.first + k >= loader.sources.size()) break;
            check_body(respawn.bodies[k], loader.sources[respawn.first + k], d, mass_once,
                       speed_once, spin_once);
        }
    }
    for (std::size_t k = 0; k < scene.throws.size() && k < loader.throw_sources.size(); ++k) {
        const Throw& t = scene.throws[k];
        const ThrowSource& source = loader.throw_sources[k];
        if (t.velocity) check_speed(length(*t.velocity), source.velocity_where,
                                    source.velocity_path, d);
        if (t.release) check_speed(length(*t.release), source.velocity_where,
                                   source.velocity_path, d);
        double fastest = 0;
        for (std::size_t p = 1; p < t.path.size(); ++p) {
            const Vec2 from = t.path[p - 1].position, to = t.path[p].position;
            fastest = std::max(fastest, length({to.x - from.x, to.y - from.y}) /
                                            (t.path[p].t - t.path[p - 1].t));
        }
        check_speed(fastest, source.path_where, source.path_path, d);
    }
    // A kinematic path's way in: from where the body starts to its first pose, when that is
    // after t = 0 (the poses' own segments are checked as they are read).
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const Body& b = scene.bodies[i];
        if (!b.kinematic || b.kinematic->path.empty() || !(b.kinematic->path[0].t > 0)) continue;
        const physics::KinematicDef::Pose& first = b.kinematic->path[0];
        const std::string path = loader.sources[i].where + ".kinematic.path[0] (from the body's "
                                                           "position and angle)";
        check_speed(length({first.position.x - b.position.x, first.position.y - b.position.y}) /
                        first.t,
                    loader.sources[i].entry, path, d);
        const double spin = std::abs(first.angle - b.angle) / first.t;
        if (spin > ranges.max_spin) {
            d.error(loader.sources[i].entry, path + ": a spin of " + number(spin) +
                                                 " rad/s is beyond any scene's; spins are at "
                                                 "most " + number(ranges.max_spin) + " rad/s");
        }
    }
}

}  // namespace discreel::scene::detail
