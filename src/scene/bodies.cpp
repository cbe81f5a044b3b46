// `bodies:` — boxes, convex polygons, capsules and circles, and the `random_polygons`
// generator with its respawns. Bodies join the discs' list (one numbering: discs, then bodies)
// and share their per-body keys (entries.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "color.hpp"
#include "discreel/shapes.hpp"
#include "entries.hpp"
#include "generators.hpp"
#include "loader.hpp"
#include "random.hpp"

namespace discreel::scene::detail {
namespace {

constexpr std::array<std::string_view, 23> entry_keys{
    "id",        "position", "velocity",    "angle",    "angular_velocity", "mass",
    "density",   "restitution", "friction", "color",    "static",           "rounding",
    "box",       "polygon",  "capsule",     "circle",   "random_polygons",  "kinematic",
    "category",  "collides", "sensor",      "label",    "label_turns"};
constexpr std::array<std::string_view, 5> shape_keys{"box", "polygon", "capsule", "circle",
                                                      "random_polygons"};
constexpr std::array<std::string_view, 2> capsule_keys{"length", "radius"};
// The per-body keys a generator applies to every body, written inside it or beside it.
constexpr std::array<std::string_view, 11> shared_body_keys{
    "id",     "mass",     "density",  "restitution", "friction", "color",
    "static", "rounding", "category", "collides",    "sensor"};
// The generator's own keys, the shared ones, and `angle`, recognised so that the message can
// say what to use instead.
constexpr std::array<std::string_view, 20> random_polygon_keys{
    "count",   "region",  "sides",       "size",     "speed",    "angular_speed",
    "respawn_every", "colors", "id",     "mass",     "density",  "restitution",
    "friction", "color",  "static",      "rounding", "category", "collides",
    "sensor",  "angle"};

// Generated polygons draw from their own streams, apart from the disc generators' (which use
// their entry's index).
constexpr std::uint64_t body_streams = std::uint64_t{1} << 32;

// The shape and its size in scene terms, with the mass and inertia it gives.
void give_shape(Body& body, const physics::Shape& shape, const Properties& p) {
    const physics::ShapeMass unit = physics::shape_mass(shape, 1.0);
    body.radius = physics::bounding_radius(shape);
    body.mass = p.mass ? *p.mass : p.density * unit.area;
    body.shape = shape;
    body.inertia = inertia_of(body);
}

std::optional<double> read_rounding(const Fields& fields, Diagnostics& d) {
    const auto v = fields.get("rounding");
    if (!v) return 0.0;
    return read_non_negative(*v, d);
}

// The shape an entry's one shape key gives; errors point at that key's value. `offset` is
// where a polygon's outline had its centroid (a polygon's position is its centroid's).
std::optional<physics::Shape> read_shape(const Fields& fields, std::string_view key,
                                         Diagnostics& d) {
    const Value value = *fields.get(key);
    const auto rounding = read_rounding(fields, d);
    if (fields.has("rounding") && (key == "capsule" || key == "circle")) {
        d.error(fields.key_location("rounding"),
                fields.path() + ": 'rounding' applies to 'box' and 'polygon'; a " +
                    std::string(key) + " is round already");
        return std::nullopt;
    }
    if (!rounding) return std::nullopt;
    const auto refused = [&](const Error& e) {
        d.error(value.where, value.path + ": " + e.message);
        return std::nullopt;
    };
    if (key == "box") {
        const auto items = read_tuple(value, 2, "[width, height]", d);
        if (!items) return std::nullopt;
        const auto w = read_positive((*items)[0], d);
        const auto h = read_positive((*items)[1], d);
        if (!w || !h) return std::nullopt;
        auto shape = physics::box_shape(*w, *h, *rounding);
        if (!shape) return refused(shape.error());
        return *shape;
    }
    if (key == "polygon") {
        const auto items = read_list(value, d);
        if (!items) return std::nullopt;
        if (items->size() > physics::max_shape_vertices || items->size() < 3) {
            return refused(Error{items->size() < 3
                                     ? "a polygon needs at least 3 points, got " +
                                           std::to_string(items->size())
                                     : "a polygon has at most 8 points, got " +
                                           std::to_string(items->size()) +
                                           "; split it into convex pieces of up to 8"});
        }
        std::vector<Vec2> points;
        for (const Value& item : *items) {
            const auto p = read_vec2(item, "[x, y]", d);
            if (!p) return std::nullopt;
            points.push_back(*p);
        }
        auto shape = physics::polygon_shape(points, *rounding);
        if (!shape) return refused(shape.error());
        return shape->shape;
    }
    if (key == "capsule") {
        const auto sub = Fields::open(value, capsule_keys, d);
        if (!sub) return std::nullopt;
        const auto length_value = required(*sub, "length", d);
        const auto radius_value = required(*sub, "radius", d);
        if (!length_value || !radius_value) return std::nullopt;
        const auto length = read_positive(*length_value, d);
        const auto radius = read_positive(*radius_value, d);
        if (!length || !radius) return std::nullopt;
        auto shape = physics::capsule_shape(*length, *radius);
        if (!shape) return refused(shape.error());
        return *shape;
    }
    return std::nullopt;   // circle: a plain disc, handled by the caller
}

void read_single_body(Loader& loader, const Fields& fields, const Value& item,
                      std::string_view key) {
    auto& d = loader.diagnostics;
    const std::size_t index = loader.scene.bodies.size();
    const Properties p = read_properties(loader, fields, item);
    auto [id, id_value, position] = read_placement(loader, fields, item);
    if (key == "circle") {   // exactly a disc of that radius
        const auto radius = read_positive(*fields.get("circle"), d);
        if (fields.has("rounding")) {
            d.error(fields.key_location("rounding"),
                    item.path + ": 'rounding' applies to 'box' and 'polygon'; a circle is round "
                                "already");
        }
        if (!room_for(loader, item, 1)) return;
        Body disc = make_disc(p, std::move(id), position.value_or(Vec2{}), radius.value_or(0),
                              index);
        const bool usable = position && radius && check_mass(disc, item, d);
        add_disc(loader, std::move(disc), item, id_value, fields.get("velocity"), usable);
        if (fields.has("label") || fields.has("label_turns")) {
        loader.labels.push_back({index, fields.get("label"), fields.get("label_turns"),
                                 item.where, item.path});
    }
        return;
    }
    const auto shape = read_shape(fields, key, d);
    if (!room_for(loader, item, 1)) return;
    Body body = make_disc(p, std::move(id), position.value_or(Vec2{}), 1.0, index);
    if (shape) give_shape(body, *shape, p);
    const bool usable = position && shape && check_mass(body, item, d);
    add_disc(loader, std::move(body), item, id_value, fields.get("velocity"), usable);
    if (fields.has("label") || fields.has("label_turns")) {
        loader.labels.push_back({index, fields.get("label"), fields.get("label_turns"),
                                 item.where, item.path});
    }
}

// A convex polygon of `sides` vertices on a circle of radius `size`: evenly spaced angles,
// each moved by less than a third of a step, so the outline stays convex with no point on a
// line between its neighbours.
std::optional<physics::Shape> random_polygon(int sides, double size, double rounding, Rng& rng) {
    const double step = 2 * std::numbers::pi / sides;
    std::vector<Vec2> points;
    for (int k = 0; k < sides; ++k) {
        const double a = step * (k + rng.uniform(-0.3, 0.3));
        points.push_back({(size - rounding) * std::cos(a), (size - rounding) * std::sin(a)});
    }
    // Convex by construction. Moving the centroid to the origin can put a point beyond
    // `size`; the outline is then scaled about the centroid to fit the circle it was placed by.
    // Sizes at the ends of double's range give outlines without area or finite corners.
    auto made = physics::polygon_shape(points, rounding);
    if (!made) return std::nullopt;
    physics::Shape shape = std::move(made->shape);
    const double bound = physics::bounding_radius(shape);
    if (bound > size) {
        const double scale = (size - rounding) / (bound - rounding);
        for (Vec2& v : shape.vertices) v = {v.x * scale, v.y * scale};
    }
    return shape;
}

struct PolygonSpec {
    RandomSpec placement;                  // count, region, size as radius, speed
    int sides_min = 3, sides_max = 8;
    double spin_min = 0, spin_max = 0;     // rad/s
    double rounding = 0;                   // metres
};

// One set: places bounding circles clear of `existing`, `walls` and each other, then gives each a
// polygon and a spin. Fewer than asked when the region is full or a polygon cannot be made
// at its size (or weighs nothing, or infinitely much).
std::vector<Body> scatter(const PolygonSpec& spec, const Properties& p,
                          const std::vector<Circle>& existing, std::span<const Wall> walls,
                          Rng& rng,
                          const std::optional<std::vector<Color>>& colors,
                          const std::string& prefix, std::size_t first_index,
                          bool& unmakeable) {
    std::vector<Body> set;
    unmakeable = false;
    for (const PlacedDisc& placed : place_random(spec.placement, existing, rng, walls)) {
        const int sides =
            spec.sides_min + static_cast<int>(rng.unit() * (spec.sides_max - spec.sides_min + 1));
        const auto shape =
            random_polygon(std::min(sides, spec.sides_max), placed.radius, spec.rounding, rng);
        if (!shape) {
            unmakeable = true;
            break;
        }
        Properties each = p;
        each.velocity = placed.velocity;
        each.angle = rng.uniform(0, 2 * std::numbers::pi);
        const double spin = rng.uniform(spec.spin_min, spec.spin_max);
        // Drawn even at no spin, so that the stream does not depend on the range; no spin is 0,
        // not a -0 that would show up in traces.
        const bool clockwise = rng.unit() < 0.5;
        each.angular_velocity = clockwise && spin != 0 ? -spin : spin;
        const std::size_t k = set.size();
        if (colors) each.color = (*colors)[k % colors->size()];
        Body body = make_disc(each, prefix + "." + std::to_string(k), placed.position, 1.0,
                              first_index + k);
        give_shape(body, *shape, each);
        if (!std::isfinite(body.mass) || !(body.mass > 0) || !std::isfinite(body.inertia)) {
            unmakeable = true;
            break;
        }
        set.push_back(std::move(body));
    }
    return set;
}

// A generator's respawns, drawn once every entry is read: a new set must keep clear of every
// static body, those declared after the generator too.
struct PendingRespawns {
    PolygonSpec spec;
    Properties properties;
    std::optional<std::vector<Color>> colors;
    std::string prefix;
    std::size_t first = 0;           // index of the generator's first body
    double every = 0;                // seconds
    Rng rng;                         // the generator's stream, after its first set
    Value item;
    Location every_where;
};

std::optional<PendingRespawns> read_random_polygons(Loader& loader, const Fields& fields,
                                                    const Value& item, std::size_t entry_index) {
    auto& d = loader.diagnostics;
    const Value spec_value = *fields.get("random_polygons");
    const auto own = Fields::open(spec_value, random_polygon_keys, d);
    if (!own) {
        loader.discs_complete = false;
        return std::nullopt;
    }
    Fields merged = fields;
    merged.adopt(*own, shared_body_keys, d);
    bool ok = true;
    if (merged.has("kinematic")) {
        d.error(merged.key_location("kinematic"),
                item.path + ": 'kinematic' moves one disc or body, not a generator's");
        ok = false;
    }
    for (const std::string_view misplaced : {"position", "velocity", "angle", "angular_velocity"}) {
        if (!merged.has(misplaced) && !own->has(misplaced)) continue;
        d.error(own->has(misplaced) ? own->key_location(misplaced) : merged.key_location(misplaced),
                item.path + ": '" + std::string(misplaced) +
                    "' does not apply to random polygons; they are placed inside 'region' with "
                    "'speed' and 'angular_speed'");
        ok = false;
    }
    const Properties p = read_properties(loader, merged, item);
    std::string prefix = "body" + std::to_string(entry_index);
    const auto id_value = merged.get("id");
    if (id_value)
        if (const auto id = read_id(*id_value, d)) prefix = *id;

    PolygonSpec spec;
    const auto count_value = required(*own, "count", d);
    const auto region_value = required(*own, "region", d);
    const auto size_value = required(*own, "size", d);
    ok = ok && count_value && region_value && size_value;
    if (count_value) {
        const auto count = read_integer(*count_value, d);
        const bool count_ok =
            count && check_between(*count_value, static_cast<double>(*count), 1,
                                   static_cast<double>(loader.limits.bodies), d);
        ok = ok && count_ok;
        if (count_ok) spec.placement.count = static_cast<std::size_t>(*count);
    }
    if (region_value) {
        const auto c = read_corners(*region_value, "[[x0, y0], [x1, y1]]", d);
        ok = ok && c;
        if (c) {
            spec.placement.region_min = {std::min(c->a.x, c->b.x), std::min(c->a.y, c->b.y)};
            spec.placement.region_max = {std::max(c->a.x, c->b.x), std::max(c->a.y, c->b.y)};
        }
    }
    if (size_value) {
        const auto r = read_range(*size_value, check_positive, d);
        ok = ok && r;
        if (r) spec.placement.radius_min = r->min, spec.placement.radius_max = r->max;
    }
    if (const auto v = own->get("sides")) {
        const auto r = read_range(*v, [](const Value& value, double x, Diagnostics& diag) {
            if (x == std::floor(x) && x >= 3 && x <= physics::max_shape_vertices) return true;
            diag.error(value.where, value.path + ": sides must be whole numbers from 3 to 8, got " +
                                        format_number(x));
            return false;
        }, d);
        ok = ok && r;
        if (r) spec.sides_min = static_cast<int>(r->min), spec.sides_max = static_cast<int>(r->max);
    }
    if (const auto v = own->get("speed")) {
        const auto r = read_range(*v, check_non_negative, d);
        ok = ok && r;
        if (r) spec.placement.speed_min = r->min, spec.placement.speed_max = r->max;
    }
    if (const auto v = own->get("angular_speed")) {
        const auto r = read_range(*v, check_non_negative, d);
        ok = ok && r;
        if (r) spec.spin_min = r->min, spec.spin_max = r->max;
    }
    if (const auto r = read_rounding(merged, d)) {
        spec.rounding = *r;
        if (size_value && ok && spec.rounding * 2 >= spec.placement.radius_min) {
            d.error(merged.key_location("rounding"),
                    item.path + ": rounding must be less than half the smallest size (" +
                        format_number(spec.placement.radius_min / 2) + " m)");
            ok = false;
        }
    } else {
        ok = false;
    }
    std::optional<double> every;
    if (const auto v = own->get("respawn_every")) {
        every = read_positive(*v, d);
        ok = ok && every;
    }
    std::optional<std::vector<Color>> colors;
    if (const auto v = own->get("colors")) {
        colors = read_colors(*v, d);
        ok = ok && colors;
        if (colors && merged.has("color")) {
            d.error(merged.key_location("color"),
                    item.path + ": 'color' and 'random_polygons.colors' both set the colour; give "
                                "only one");
            ok = false;
        }
    }
    if (!ok || !room_for(loader, item, spec.placement.count)) {
        loader.discs_complete = false;
        return std::nullopt;
    }
    std::vector<Circle> existing;
    for (std::size_t i = 0; i < loader.scene.bodies.size(); ++i) {
        const Body& body = loader.scene.bodies[i];
        if (loader.sources[i].usable)
            existing.push_back({body.position, body.radius, body.is_static});
    }
    Rng rng(loader.scene.physics.seed, body_streams + entry_index);
    const std::size_t first = loader.scene.bodies.size();
    bool unmakeable = false;
    std::vector<Body> set =
        scatter(spec, p, existing, loader.scene.walls, rng, colors, prefix, first, unmakeable);
    if (unmakeable) {
        d.error(own->get("size")->where,
                own->get("size")->path + ": polygons of this size have no finite, positive area "
                                         "or mass; choose sizes nearer 1 m");
        loader.discs_complete = false;
        return std::nullopt;
    }
    if (set.size() < spec.placement.count) {
        d.error(item.where, item.path + ": could place only " + std::to_string(set.size()) +
                                " of " + std::to_string(spec.placement.count) +
                                " polygons without overlap; make the region larger, the sizes "
                                "smaller or the count lower");
        loader.discs_complete = false;
        return std::nullopt;
    }
    const auto speed_value = own->get("speed");
    for (Body& body : set) add_disc(loader, std::move(body), item, id_value, speed_value, true);
    if (!every) return std::nullopt;
    return PendingRespawns{spec, p, colors, prefix, first, *every, rng, item,
                           own->key_location("respawn_every")};
}

// Every respawn of every generator, in order of time (a tie keeps declaration order). Each set
// is held in memory from the start, so each counts against the limit on bodies.
void draw_respawns(Loader& loader, std::vector<PendingRespawns>& pending) {
    auto& d = loader.diagnostics;
    std::vector<Circle> fixed;   // the bodies that never move; the others will have moved
    for (std::size_t i = 0; i < loader.scene.bodies.size(); ++i) {
        const Body& body = loader.scene.bodies[i];
        if (body.is_static && loader.sources[i].usable)
            fixed.push_back({body.position, body.radius, true});
    }
    std::size_t total = loader.scene.bodies.size();
    // A clip length the caller will refuse (beyond the limit) draws only the file's respawns.
    const auto& given = loader.clip_duration;
    const double clip = given && *given > 0 && *given <= loader.limits.duration
                            ? *given
                            : loader.scene.video.duration;
    for (PendingRespawns& g : pending) {
        const Value& item = g.item;
        for (double k = 1; k * g.every < clip; ++k) {
            const double at = k * g.every;
            total += g.spec.placement.count;
            if (total > loader.limits.bodies) {
                d.error(g.every_where,
                        item.path + ".respawn_every: respawning every " + format_number(g.every) +
                            " s brings the scene to " + std::to_string(total) +
                            " bodies over the clip; the limit is " +
                            std::to_string(loader.limits.bodies) + " (raise it with --max-bodies)");
                return;
            }
            bool unmakeable = false;
            Respawn r;
            r.at = at;
            r.first = g.first;
            r.bodies = scatter(g.spec, g.properties, fixed, loader.scene.walls, g.rng, g.colors,
                               g.prefix, g.first, unmakeable);
            if (r.bodies.size() < g.spec.placement.count) {
                d.error(item.where, item.path + ": the respawn at t = " + format_number(at) +
                                        " s could place only " + std::to_string(r.bodies.size()) +
                                        " of " + std::to_string(g.spec.placement.count) +
                                        " polygons");
                return;
            }
            loader.scene.respawns.push_back(std::move(r));
        }
    }
    std::stable_sort(loader.scene.respawns.begin(), loader.scene.respawns.end(),
                     [](const Respawn& a, const Respawn& b) { return a.at < b.at; });
}

}  // namespace

void read_bodies(Loader& loader, const Value& value) {
    auto& d = loader.diagnostics;
    const auto items = read_list(value, d);
    if (!items) {
        loader.discs_complete = false;
        return;
    }
    std::vector<PendingRespawns> pending;
    for (std::size_t i = 0; i < items->size() && !d.full() && !loader.disc_limit_reached; ++i) {
        const Value& item = (*items)[i];
        const auto fields = Fields::open(item, entry_keys, d);
        if (!fields) {
            loader.discs_complete = false;
            continue;
        }
        std::vector<std::string_view> given;
        for (const std::string_view key : shape_keys)
            if (fields->has(key)) given.push_back(key);
        if (given.empty()) {
            d.error(item.where, item.path + ": give the body's shape: one of 'box', 'polygon', "
                                            "'capsule', 'circle' or 'random_polygons'");
            loader.discs_complete = false;
            continue;
        }
        if (given.size() > 1) {
            d.error(fields->key_location(given[1]),
                    item.path + ": a body has one shape; '" + std::string(given[0]) + "' and '" +
                        std::string(given[1]) + "' are both given");
            loader.discs_complete = false;
            continue;
        }
        if (given[0] == "random_polygons") {
            if (auto respawns = read_random_polygons(loader, *fields, item, i))
                pending.push_back(std::move(*respawns));
        } else {
            read_single_body(loader, *fields, item, given[0]);
        }
    }
    if (!d.full() && !loader.disc_limit_reached) draw_respawns(loader, pending);
}

}  // namespace discreel::scene::detail
