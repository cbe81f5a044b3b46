// `kinematic:` on a disc or body — a moving platform, a windmill's sails: moved as told.
#include <array>
#include <string_view>

#include "entries.hpp"
#include "loader.hpp"

namespace discreel::scene::detail {
namespace {

constexpr std::array<std::string_view, 4> kinematic_keys{"velocity", "angular_velocity", "path",
                                                         "loop"};

// [t, x, y, angle] waypoints, at least one, times at least 0 and strictly increasing.
bool read_poses(const Value& value, std::vector<physics::KinematicDef::Pose>& poses,
                Diagnostics& d) {
    const auto items = read_list(value, d);
    if (!items) return false;
    if (items->empty()) {
        d.error(value.where, value.path + ": a path needs at least 1 pose [t, x, y, angle]");
        return false;
    }
    if (items->size() > max_waypoints) {
        d.error(value.where, value.path + ": too many poses (" + std::to_string(items->size()) +
                                 "); the limit is " + std::to_string(max_waypoints));
        return false;
    }
    bool ok = true;
    for (const Value& item : *items) {
        const auto numbers = read_tuple(item, 4, "[t, x, y, angle]", d);
        if (!numbers) {
            ok = false;
            continue;
        }
        std::array<std::optional<double>, 4> v;
        for (std::size_t k = 0; k < 4; ++k) v[k] = read_number((*numbers)[k], d);
        if (!v[0] || !v[1] || !v[2] || !v[3]) {
            ok = false;
            continue;
        }
        if (*v[0] < 0 || (!poses.empty() && *v[0] <= poses.back().t)) {
            d.error((*numbers)[0].where,
                    item.path + ": pose times must be at least 0 and increase strictly, but " +
                        format_number(*v[0]) +
                        (poses.empty() ? std::string(" is below 0")
                                       : " comes after " + format_number(poses.back().t)));
            ok = false;
            continue;
        }
        poses.push_back({*v[0], {*v[1], *v[2]}, *v[3]});
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
    }
    if (const auto v = fields->get("angular_velocity")) {
        const auto omega = read_number(*v, d);
        ok = ok && omega;
        k.angular_velocity = omega.value_or(0);
    }
    if (const auto v = fields->get("path")) ok = read_poses(*v, k.path, d) && ok;
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
