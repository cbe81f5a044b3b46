// `throws:` — flicks and grabs, and which disc each one moves.
#include <array>
#include <string_view>

#include "disc_ref.hpp"
#include "loader.hpp"

namespace discreel::scene::detail {
namespace {

// `body` is the same as `disc`: bodies of every shape share the discs' numbering.
constexpr std::array<std::string_view, 6> throw_keys{"disc", "body", "at", "velocity", "path",
                                                     "release"};

bool read_path(Loader& loader, const Value& value, Throw& t) {
    const auto points = read_timed_points(value, {3, "[t, x, y]", "waypoint", "a grab", 2},
                                          loader.diagnostics);
    if (!points) return false;
    for (const TimedPoint& p : *points) {
        t.path.push_back({p.numbers[0], {p.numbers[1], p.numbers[2]}});
    }
    t.at = t.path.front().t;
    return true;
}

}  // namespace

void read_throws(Loader& loader, const Value& value) {
    auto& d = loader.diagnostics;
    const auto items = read_list(value, d);
    if (!items) return;
    if (items->size() > max_throws) {
        d.error(value.where, value.path + ": too many throws (" + std::to_string(items->size()) +
                                 "); the limit is " + std::to_string(max_throws));
        return;
    }
    const DiscIds ids(loader.scene.bodies);

    for (const Value& item : *items) {
        if (d.full()) break;
        const auto fields = Fields::open(item, throw_keys, d);
        if (!fields) continue;
        Throw t;
        bool ok = true;
        if (fields->has("disc") && fields->has("body")) {
            d.error(fields->key_location(fields->later_of("disc", "body")),
                    item.path + ": give 'disc' or 'body', not both (they mean the same)");
            ok = false;
        } else if (const auto disc = fields->get(fields->has("body") ? "body" : "disc")) {
            const auto index = resolve_disc(loader, *disc, ids);
            if (index && loader.scene.bodies[*index].is_static) {
                const Body& body = loader.scene.bodies[*index];
                d.error(disc->where, disc->path + (body.shape ? ": body '" : ": disc '") + body.id +
                                         "' is static and cannot be thrown");
                ok = false;
            } else if (index && loader.scene.bodies[*index].kinematic) {
                d.error(disc->where, disc->path + ": body '" + loader.scene.bodies[*index].id +
                                         "' is kinematic: it moves as its 'kinematic' says and "
                                         "cannot be thrown");
                ok = false;
            }
            ok = ok && index;
            t.body = index.value_or(0);
        } else {
            d.error(item.where, item.path + ": missing required key 'disc' (or 'body')");
            ok = false;
        }
        const bool is_grab = fields->has("path");
        if (is_grab && fields->has("velocity")) {
            d.error(fields->key_location(fields->later_of("velocity", "path")),
                    item.path + ": a throw is either a flick ('velocity') or a grab ('path'), "
                                "not both");
            ok = false;
        } else if (!is_grab && !fields->has("velocity")) {
            d.error(item.where, item.path + ": a throw needs 'velocity' (a flick) or 'path' "
                                            "(a grab)");
            ok = false;
        }
        if (is_grab && fields->has("at")) {
            d.error(fields->key_location("at"),
                    item.path + ": 'at' is for flicks; a grab starts at the time of its first "
                                "waypoint");
            ok = false;
        }
        if (!is_grab && fields->has("release")) {
            d.error(fields->key_location("release"),
                    item.path + ": 'release' is for grabs; it needs a 'path'");
            ok = false;
        }
        if (const auto at = fields->get("at")) {
            const auto v = read_non_negative(*at, d);
            ok = ok && v;
            t.at = v.value_or(0);
        }
        if (const auto velocity = fields->get("velocity")) {
            t.velocity = read_vec2(*velocity, "[x, y]", d);
            ok = ok && t.velocity;
        }
        if (const auto path = fields->get("path")) ok = read_path(loader, *path, t) && ok;
        if (const auto release = fields->get("release")) {
            t.release = read_vec2(*release, "[x, y]", d);
            ok = ok && t.release;
        }
        if (ok) {
            ThrowSource source{item.where, item.path, item.where, item.path};
            if (const auto v = fields->get(is_grab ? "release" : "velocity")) {
                source.velocity_where = v->where;
                source.velocity_path = v->path;
            }
            if (const auto v = fields->get("path")) {
                source.path_where = v->where;
                source.path_path = v->path;
            }
            loader.throw_sources.push_back(std::move(source));
            loader.scene.throws.push_back(std::move(t));
        }
    }
}

}  // namespace discreel::scene::detail
