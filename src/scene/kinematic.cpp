// `kinematic:` on a disc or body — a moving platform, a windmill's sails: moved as told.
#include <array>
#include <cmath>
#include <string>
#include <string_view>

#include "entries.hpp"
#include "loader.hpp"

namespace discreel::scene::detail {
namespace {

constexpr std::array<std::string_view, 4> kinematic_keys{"velocity", "angular_velocity", "path",
                                                         "loop"};

// A speed (m/s) or spin (rad/s) beyond scene::ranges, refused at `where` as a body's is.
bool within(double value, double most, const char* what, const char* unit,
            const Location& where, const std::string& path, Diagnostics& d) {
    if (std::abs(value) <= most) return true;
    d.error(where, path + ": a " + what + " of " + format_bound(std::abs(value)) + " " + unit +
                       " is beyond any scene's; " + what + "s are at most " + format_bound(most) +
                       " " + unit);
    return false;
}

// [t, x, y, angle] poses, at least one; the speed and turning rate between each two within
// scene::ranges.
bool read_poses(const Value& value, std::vector<physics::KinematicDef::Pose>& poses,
                Diagnostics& d) {
    const auto points =
        read_timed_points(value, {4, "[t, x, y, angle]", "pose", "a path", 1}, d);
    if (!points) return false;
    bool ok = true;
    for (const TimedPoint& p : *points) {
        const auto [t, x, y, angle] = p.numbers;
        if (!poses.empty()) {
            const physics::KinematicDef::Pose& from = poses.back();
            const double dt = t - from.t;
            const double speed = std::hypot(x - from.position.x, y - from.position.y) / dt;
            const std::string path = p.item.path + " (from the pose before)";
            ok = within(speed, ranges.max_speed, "speed", "m/s", p.item.where, path, d) && ok;
            ok = within((angle - from.angle) / dt, ranges.max_spin, "spin", "rad/s",
                        p.item.where, path, d) &&
                 ok;
        }
        poses.push_back({t, {x, y}, angle});
    }
    return ok;
}

}  // namespace

std::optional<physics::KinematicDef> read_kinematic(const Value& value, Diagnostics& d) {
    const auto fields = Fields::open(value, kinematic_keys, d);
    if (!fields) return std::nullopt;
    physics::KinematicDef k;
    bool ok = true;
    const bool steady = fields->has("velocity") || fields->has("angular_velocity");
    if (fields->has("path") && steady) {
        const std::string_view steady_key = fields->has("velocity") ? "velocity" : "angular_velocity";
        d.error(fields->key_location(fields->later_of("path", steady_key)),
                value.path + ": give a 'path' or a 'velocity' and 'angular_velocity', not both");
        return std::nullopt;
    }
    if (const auto v = fields->get("velocity")) {
        const auto velocity = read_vec2(*v, "[x, y]", d);
        ok = ok && velocity;
        k.velocity = velocity.value_or(Vec2{});
        ok = within(std::hypot(k.velocity.x, k.velocity.y), ranges.max_speed, "speed", "m/s",
                    v->where, v->path, d) && ok;
    }
    if (const auto v = fields->get("angular_velocity")) {
        const auto omega = read_number(*v, d);
        ok = ok && omega;
        k.angular_velocity = omega.value_or(0);
        ok = within(k.angular_velocity, ranges.max_spin, "spin", "rad/s", v->where, v->path, d) &&
             ok;
    }
    if (const auto v = fields->get("path")) {
        ok = read_poses(*v, k.path, d) && ok;
    }
    if (const auto v = fields->get("loop")) {
        if (!fields->has("path")) {
            d.error(fields->key_location("loop"), value.path + ": 'loop' needs a 'path'");
            ok = false;
        } else if (const auto loop = read_bool(*v, d)) {
            k.loop = *loop;
        } else {
            ok = false;
        }
    }
    if (!ok) return std::nullopt;
    return k;
}

}  // namespace discreel::scene::detail
