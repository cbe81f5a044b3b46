// `discs:` — single discs and the `grid` and `random` generators, and the checks on the
// resulting list (unique ids, no overlaps at t = 0).
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <span>
#include <string_view>

#include "color.hpp"
#include "discreel/physics.hpp"
#include "entries.hpp"
#include "generators.hpp"
#include "loader.hpp"
#include "overlap.hpp"
#include "random.hpp"

namespace discreel::scene::detail {
namespace {

constexpr std::array<std::string_view, 20> entry_keys{
    "id",        "position",    "velocity", "angle",  "angular_velocity", "radius", "mass",
    "density",   "restitution", "friction", "color",  "static",           "grid",   "random",
    "kinematic", "category",    "collides", "sensor", "label", "label_turns"};
// A generator's own keys, followed by the per-disc keys it applies to every disc. Those may be
// written inside `grid:` (as docs/scene-format.md shows) or beside it; `position` is recognised
// only so that the message can say what to use instead.
constexpr std::array<std::string_view, 13> shared_disc_keys{
    "id",       "velocity",    "angle",    "angular_velocity", "mass",     "density",  "restitution",
    "friction", "color",       "static",   "category",         "collides", "sensor"};
constexpr std::array<std::string_view, 20> grid_keys{
    "origin", "count",    "spacing",     "radius",   "jitter", "colors", "id",   "velocity",
    "angle",  "angular_velocity", "mass", "density", "restitution", "friction", "color", "static",
    "category", "collides", "sensor", "position"};
constexpr std::array<std::string_view, 19> random_keys{
    "count", "radius",  "region", "speed",   "colors",      "id",       "velocity", "angle",
    "angular_velocity", "mass", "density", "restitution", "friction", "color", "static",
    "category", "collides", "sensor", "position"};

}  // namespace

Properties read_properties(Loader& loader, const Fields& fields, const Value& item) {
    auto& d = loader.diagnostics;
    Properties p;
    p.restitution = loader.scene.physics.restitution;
    p.friction = loader.scene.physics.friction;
    if (const auto v = fields.get("velocity"))
        if (const auto velocity = read_vec2(*v, "[x, y]", d)) p.velocity = *velocity;
    if (const auto v = fields.get("angle"))
        if (const auto angle = read_number(*v, d)) p.angle = *angle;
    if (const auto v = fields.get("angular_velocity"))
        if (const auto omega = read_number(*v, d)) p.angular_velocity = *omega;
    if (fields.has("mass") && fields.has("density")) {
        d.error(fields.key_location(fields.later_of("mass", "density")),
                item.path + ": give either 'mass' or 'density', not both");
    } else if (const auto v = fields.get("mass")) {
        p.mass = read_positive(*v, d);
    } else if (const auto v = fields.get("density")) {
        if (const auto density = read_positive(*v, d)) p.density = *density;
    }
    if (const auto v = fields.get("restitution"))
        if (const auto e = read_between(*v, 0, 1, d)) p.restitution = *e;
    if (const auto v = fields.get("friction"))
        if (const auto mu = read_non_negative(*v, d)) p.friction = *mu;
    if (const auto v = fields.get("color")) p.color = read_color(*v, d);
    if (const auto v = fields.get("static"))
        if (const auto s = read_bool(*v, d)) p.is_static = *s;
    read_filter(loader, fields, p.category, p.collides);
    if (const auto v = fields.get("sensor"))
        if (const auto s = read_bool(*v, d)) p.sensor = *s;
    if (const auto v = fields.get("kinematic")) {
        if (p.is_static) {
            d.error(fields.key_location("kinematic"),
                    item.path + ": a body is 'static' or 'kinematic', not both");
        } else {
            p.kinematic = read_kinematic(*v, d);
        }
    }
    return p;
}

bool valid_id_character(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
           c == '_' || c == '-' || c == '.';
}

// Ids end up in CSV traces and in messages, so they are kept to a safe alphabet.
std::optional<std::string> read_id(const Value& value, Diagnostics& d) {
    if (!value.node.IsScalar()) {
        d.error(value.where, value.path + ": expected a name, got " + describe(value.node));
        return std::nullopt;
    }
    const std::string& id = value.node.Scalar();
    if (id.empty() || !std::all_of(id.begin(), id.end(), valid_id_character)) {
        d.error(value.where, value.path + ": " + describe(value.node) +
                                 " is not a valid id; use letters, digits, '_', '-' and '.'");
        return std::nullopt;
    }
    return id;
}

Body make_disc(const Properties& p, std::string id, Vec2 position, double radius,
               std::size_t index) {
    Body disc;
    disc.id = std::move(id);
    disc.position = position;
    disc.velocity = p.velocity;
    disc.angle = p.angle;
    disc.angular_velocity = p.angular_velocity;
    disc.radius = radius;
    disc.mass = p.mass ? *p.mass : p.density * std::numbers::pi * radius * radius;
    disc.restitution = p.restitution;
    disc.friction = p.friction;
    disc.color = p.color ? *p.color : palette_color(index);
    disc.is_static = p.is_static;
    disc.kinematic = p.kinematic;
    disc.category = p.category;
    disc.collides = p.collides;
    disc.sensor = p.sensor;
    disc.inertia = inertia_of(disc);
    return disc;
}

double inertia_of(const Body& body) {
    if (body.is_static) return 0.0;
    physics::BodyDef def;
    def.radius = body.radius;
    def.mass = body.mass;
    def.shape = body.shape;
    return physics::inertia_of(def);
}

// A mass from density * pi r^2 can overflow or underflow for absurd radii; physics divides
// by it, so it must come out positive and finite.
bool check_mass(const Body& disc, const Value& item, Diagnostics& d) {
    if (std::isfinite(disc.mass) && disc.mass > 0) return true;
    d.error(item.where, item.path + ": the mass works out to " + format_number(disc.mass) +
                            " kg (density * pi * radius^2); choose a radius or density that "
                            "gives a positive, finite mass");
    return false;
}

// Whether `count` more bodies (discs or shapes) still fit under the limit; reports the entry
// that breaks it.
bool room_for(Loader& loader, const Value& item, std::size_t count) {
    const std::size_t total = loader.scene.bodies.size() + count;
    if (total <= loader.limits.bodies) return true;
    loader.diagnostics.error(item.where, item.path + ": this entry brings the scene to " +
                                             std::to_string(total) + " bodies; the limit is " +
                                             std::to_string(loader.limits.bodies) +
                                             " (raise it with --max-bodies)");
    loader.discs_complete = false;
    loader.disc_limit_reached = true;
    return false;
}

void add_disc(Loader& loader, Body disc, const Value& item, const std::optional<Value>& id_value,
              const std::optional<Value>& velocity_value, bool usable) {
    BodySource source{.entry = item.where,
                      .where = item.path,
                      .id_where = item.where,
                      .id_path = item.path,
                      .velocity_where = item.where,
                      .velocity_path = item.path,
                      .usable = usable};
    if (id_value) {
        source.id_where = id_value->where;
        source.id_path = id_value->path;
    }
    if (velocity_value) {
        source.velocity_where = velocity_value->where;
        source.velocity_path = velocity_value->path;
    }
    disc.line = item.where.line;
    disc.column = item.where.column;
    loader.scene.bodies.push_back(std::move(disc));
    loader.sources.push_back(std::move(source));
}

Placement read_placement(Loader& loader, const Fields& fields, const Value& item) {
    auto& d = loader.diagnostics;
    Placement placement;
    placement.id = std::to_string(loader.scene.bodies.size());
    placement.id_value = fields.get("id");
    if (placement.id_value)
        if (const auto explicit_id = read_id(*placement.id_value, d)) placement.id = *explicit_id;
    if (const auto v = fields.get("position"))
        placement.position = read_vec2(*v, "[x, y]", d);
    else
        d.error(item.where, item.path + ": missing required key 'position'");
    return placement;
}

namespace {

void read_single_disc(Loader& loader, const Fields& fields, const Value& item) {
    auto& d = loader.diagnostics;
    const std::size_t index = loader.scene.bodies.size();
    const Properties p = read_properties(loader, fields, item);
    auto [id, id_value, position] = read_placement(loader, fields, item);
    std::optional<double> radius;
    if (const auto v = fields.get("radius"))
        radius = read_positive(*v, d);
    else
        d.error(item.where, item.path + ": missing required key 'radius'");
    if (!room_for(loader, item, 1)) return;
    Body disc = make_disc(p, std::move(id), position.value_or(Vec2{}), radius.value_or(0),
                          index);
    const bool usable = position && radius && check_mass(disc, item, d);
    add_disc(loader, std::move(disc), item, id_value, fields.get("velocity"), usable);
    if (fields.has("label") || fields.has("label_turns")) {
        loader.labels.push_back({index, fields.get("label"), fields.get("label_turns"),
                                 item.where, item.path});
    }
}

}  // namespace

std::optional<std::vector<Color>> read_colors(const Value& value, Diagnostics& d) {
    const auto items = read_list(value, d);
    if (!items) return std::nullopt;
    if (items->empty()) {
        d.error(value.where, value.path + ": list at least one colour");
        return std::nullopt;
    }
    std::vector<Color> colors;
    bool ok = true;
    for (const Value& item : *items) {
        const auto c = read_color(item, d);
        ok = ok && c.has_value();
        if (c) colors.push_back(*c);
    }
    if (!ok) return std::nullopt;
    return colors;
}

std::optional<Value> required(const Fields& fields, std::string_view key, Diagnostics& d) {
    auto value = fields.get(key);
    if (!value)
        d.error(fields.where(), fields.path() + ": missing required key '" + std::string(key) + "'");
    return value;
}

namespace {

double max_discs_of(const Loader& loader) { return static_cast<double>(loader.limits.bodies); }

std::string position_hint(std::string_view kind) {
    return kind == "grid" ? "'position' does not apply to a grid; give the centre of its first "
                            "disc as 'origin' inside 'grid:'"
                          : "'position' does not apply to random discs; they are placed inside "
                            "'region'";
}

// `position` written inside `grid:` or `random:`. True if so.
bool report_misplaced_position(const Fields& fields, std::string_view kind, Diagnostics& d) {
    if (!fields.has("position")) return false;
    d.error(fields.key_location("position"), fields.path() + ": " + position_hint(kind));
    return true;
}

// What a generator entry produces before the shared properties are applied.
struct Generated {
    std::vector<Vec2> positions;
    std::vector<Vec2> velocities;     // empty: every disc takes the entry's velocity
    std::vector<double> radii;
    std::optional<std::vector<Color>> colors;
};

std::optional<Generated> read_grid(Loader& loader, const Fields& fields, Rng& rng) {
    auto& d = loader.diagnostics;
    const auto count_value = required(fields, "count", d);
    const auto radius_value = required(fields, "radius", d);
    bool ok = count_value && radius_value && !report_misplaced_position(fields, "grid", d);

    GridSpec spec;
    if (const auto v = fields.get("origin")) {
        const auto origin = read_vec2(*v, "[x, y]", d);
        ok = ok && origin;
        spec.origin = origin.value_or(Vec2{});
    }
    std::optional<double> radius;
    if (radius_value) radius = read_positive(*radius_value, d);
    if (const auto v = fields.get("jitter")) {
        const auto jitter = read_non_negative(*v, d);
        ok = ok && jitter;
        spec.jitter = jitter.value_or(0);
    }
    if (const auto v = fields.get("spacing")) {
        if (const auto items = read_tuple(*v, 2, "[x, y]", d)) {
            const auto x = read_positive((*items)[0], d);
            const auto y = read_positive((*items)[1], d);
            ok = ok && x && y;
            spec.spacing = {x.value_or(0), y.value_or(0)};
        } else {
            ok = false;
        }
    } else if (radius) {
        // Default: neighbours just touch, even when both are jittered towards each other.
        const double pitch = 2 * *radius + 2 * spec.jitter;
        spec.spacing = {pitch, pitch};
    }
    if (count_value) {
        if (const auto items = read_tuple(*count_value, 2, "[columns, rows]", d)) {
            const auto columns = read_integer((*items)[0], d);
            const auto rows = read_integer((*items)[1], d);
            const bool columns_ok = columns && check_between((*items)[0], static_cast<double>(*columns), 1, max_discs_of(loader), d);
            const bool rows_ok = rows && check_between((*items)[1], static_cast<double>(*rows), 1, max_discs_of(loader), d);
            if (columns_ok && rows_ok &&
                *columns * *rows > static_cast<long long>(loader.limits.bodies)) {
                d.error(count_value->where,
                        count_value->path + ": " + std::to_string(*columns) + " x " +
                            std::to_string(*rows) + " = " + std::to_string(*columns * *rows) +
                            " discs is more than the limit of " +
                            std::to_string(loader.limits.bodies) +
                            " bodies (raise it with --max-bodies)");
                ok = false;
            }
            ok = ok && columns_ok && rows_ok;
            if (ok) {
                spec.columns = static_cast<int>(*columns);
                spec.rows = static_cast<int>(*rows);
            }
        } else {
            ok = false;
        }
    }
    Generated g;
    if (const auto v = fields.get("colors")) {
        g.colors = read_colors(*v, d);
        ok = ok && g.colors;
    }
    if (!ok || !radius) return std::nullopt;
    g.positions = grid_positions(spec, rng);
    g.radii.assign(g.positions.size(), *radius);
    return g;
}

std::optional<Generated> read_random(Loader& loader, const Fields& fields, const Value& value,
                                     Rng& rng) {
    auto& d = loader.diagnostics;
    const auto count_value = required(fields, "count", d);
    const auto region_value = required(fields, "region", d);
    const auto radius_value = required(fields, "radius", d);
    bool ok = count_value && region_value && radius_value &&
              !report_misplaced_position(fields, "random", d);

    RandomSpec spec;
    if (count_value) {
        const auto count = read_integer(*count_value, d);
        const bool count_ok = count && check_between(*count_value, static_cast<double>(*count), 1, max_discs_of(loader), d);
        ok = ok && count_ok;
        if (count_ok) spec.count = static_cast<std::size_t>(*count);
    }
    if (region_value) {
        const auto c = read_corners(*region_value, "[[x0, y0], [x1, y1]]", d);
        ok = ok && c;
        if (c) {
            spec.region_min = {std::min(c->a.x, c->b.x), std::min(c->a.y, c->b.y)};
            spec.region_max = {std::max(c->a.x, c->b.x), std::max(c->a.y, c->b.y)};
            if (spec.region_min.x == spec.region_max.x || spec.region_min.y == spec.region_max.y) {
                d.error(region_value->where,
                        region_value->path + ": the region has no area; its two corners must "
                                             "differ in both x and y");
                ok = false;
            }
        }
    }
    if (radius_value) {
        const auto r = read_range(*radius_value, check_positive, d);
        ok = ok && r;
        if (r) spec.radius_min = r->min, spec.radius_max = r->max;
    }
    if (const auto v = fields.get("speed")) {
        const auto s = read_range(*v, check_non_negative, d);
        ok = ok && s;
        if (s) spec.speed_min = s->min, spec.speed_max = s->max;
    }
    Generated g;
    if (const auto v = fields.get("colors")) {
        g.colors = read_colors(*v, d);
        ok = ok && g.colors;
    }
    if (!ok) return std::nullopt;

    std::vector<Circle> existing;
    existing.reserve(loader.scene.bodies.size());
    for (std::size_t i = 0; i < loader.scene.bodies.size(); ++i) {
        const Body& disc = loader.scene.bodies[i];
        if (loader.sources[i].usable) existing.push_back({disc.position, disc.radius, disc.is_static});
    }
    const auto placed = place_random(spec, existing, rng);
    if (placed.size() < spec.count) {
        d.error(value.where, value.path + ": could place only " + std::to_string(placed.size()) +
                                 " of " + std::to_string(spec.count) +
                                 " discs without overlap; make the region larger, the discs "
                                 "smaller or the count lower");
        return std::nullopt;
    }
    for (const PlacedDisc& p : placed) {
        g.positions.push_back(p.position);
        g.velocities.push_back(p.velocity);
        g.radii.push_back(p.radius);
    }
    return g;
}

void read_generator(Loader& loader, const Fields& fields, const Value& item,
                    std::size_t entry_index) {
    auto& d = loader.diagnostics;
    const bool is_grid = fields.has("grid");
    const std::string kind = is_grid ? "grid" : "random";
    bool ok = true;
    if (fields.has("grid") && fields.has("random")) {
        d.error(fields.key_location(fields.later_of("grid", "random")),
                item.path + ": an entry can have 'grid' or 'random', not both");
        loader.discs_complete = false;
        return;
    }
    if (fields.has("position")) {
        d.error(fields.key_location("position"), item.path + ": " + position_hint(kind));
        ok = false;
    }
    if (fields.has("radius")) {
        d.error(fields.key_location("radius"),
                item.path + ": 'radius' belongs inside '" + kind + ":'");
        ok = false;
    }
    const Value spec = *fields.get(kind);
    const auto generator_fields =
        is_grid ? Fields::open(spec, grid_keys, d) : Fields::open(spec, random_keys, d);
    if (!generator_fields) {
        loader.discs_complete = false;
        return;
    }
    Fields merged = fields;
    merged.adopt(*generator_fields, shared_disc_keys, d);
    if (merged.has("kinematic")) {
        d.error(merged.key_location("kinematic"),
                item.path + ": 'kinematic' moves one disc or body, not a generator's");
        ok = false;
    }
    if (!is_grid && merged.has("velocity")) {
        d.error(merged.key_location("velocity"),
                item.path + ": 'velocity' cannot be used with 'random'; give 'speed: [min, max]' "
                            "inside 'random:' instead");
        ok = false;
    }
    const Properties p = read_properties(loader, merged, item);
    std::string prefix = std::to_string(entry_index);
    const auto id_value = merged.get("id");
    if (id_value)
        if (const auto id = read_id(*id_value, d)) prefix = *id;

    Rng rng(loader.scene.physics.seed, entry_index);
    const auto generated = is_grid ? read_grid(loader, *generator_fields, rng)
                                   : read_random(loader, *generator_fields, spec, rng);
    if (generated && generated->colors && merged.has("color")) {
        d.error(merged.key_location("color"),
                item.path + ": 'color' and '" + kind + ".colors' both set the colour; give only one");
        ok = false;
    }
    if (!generated || !ok || !room_for(loader, item, generated->positions.size())) {
        loader.discs_complete = false;
        return;
    }
    // What the speed check points at: the velocity every disc of a grid shares, or the range a
    // random entry draws its speeds from.
    const auto velocity_value = is_grid ? merged.get("velocity") : generator_fields->get("speed");
    bool mass_ok = true;
    for (std::size_t k = 0; k < generated->positions.size(); ++k) {
        Properties each = p;
        if (!generated->velocities.empty()) each.velocity = generated->velocities[k];
        if (generated->colors) each.color = (*generated->colors)[k % generated->colors->size()];
        Body disc = make_disc(each, prefix + "." + std::to_string(k), generated->positions[k],
                              generated->radii[k], loader.scene.bodies.size());
        // One report per entry is enough: every disc of it shares the cause.
        const bool usable = mass_ok && check_mass(disc, item, d);
        mass_ok = mass_ok && usable;
        add_disc(loader, std::move(disc), item, id_value, velocity_value, usable);
    }
}

}  // namespace

void read_discs(Loader& loader, const Value& value) {
    auto& d = loader.diagnostics;
    const auto items = read_list(value, d);
    if (!items) {
        loader.discs_complete = false;
        return;
    }
    for (std::size_t i = 0; i < items->size() && !d.full(); ++i) {
        const Value& item = (*items)[i];
        const auto fields = Fields::open(item, entry_keys, d);
        if (!fields) {
            loader.discs_complete = false;
            continue;
        }
        if (fields->has("grid") || fields->has("random"))
            read_generator(loader, *fields, item, i);
        else
            read_single_disc(loader, *fields, item);
        if (loader.disc_limit_reached) break;
    }
}

// A coordinate x carries a rounding error of about 1e-16 |x|; a disc must be large against the
// error of the positions around it, or rounding decides its contacts.
static void check_radii_against_reach(Loader& loader) {
    constexpr double min_radius_per_reach = 1e-9;
    auto& d = loader.diagnostics;
    const auto& discs = loader.scene.bodies;
    double reach = 0;   // metres from the origin to the farthest coordinate
    const auto extend = [&](Vec2 p) { reach = std::max({reach, std::abs(p.x), std::abs(p.y)}); };
    for (const Body& disc : discs) {
        extend(disc.position);
        if (!disc.kinematic) continue;
        for (const physics::KinematicDef::Pose& pose : disc.kinematic->path) extend(pose.position);
    }
    for (const Wall& wall : loader.scene.walls) {
        extend(wall.a);
        extend(wall.b);
    }
    const double smallest = min_radius_per_reach * reach;
    std::optional<Location> reported;   // once per entry: a generator makes many alike
    for (std::size_t i = 0; i < discs.size() && !d.full(); ++i) {
        const BodySource& source = loader.sources[i];
        if (!source.usable || discs[i].radius >= smallest) continue;
        if (reported && reported->line == source.entry.line &&
            reported->column == source.entry.column)
            continue;
        reported = source.entry;
        d.error(source.entry, source.where + ": a radius of " + format_number(discs[i].radius) +
                                  " m is too small for a scene reaching " + format_number(reach) +
                                  " m from the origin; radii must be at least 1e-9 of that (" +
                                  format_number(smallest) + " m) for positions to stay precise");
    }
}

// How deep two bodies' outlines overlap at t = 0 (negative: the gap between them), metres.
static double shape_overlap(const Body& a, const Body& b) {
    const auto shape_of = [](const Body& body) {
        return body.shape ? *body.shape : physics::circle_shape(body.radius);
    };
    return -physics::separation(shape_of(a), a.position, a.angle, shape_of(b), b.position,
                                b.angle, 0.0);
}

void check_discs(Loader& loader) {
    auto& d = loader.diagnostics;
    const auto& discs = loader.scene.bodies;
    const auto& sources = loader.sources;

    std::map<std::string, std::size_t> first_with_id;
    for (std::size_t i = 0; i < discs.size() && !d.full(); ++i) {
        const auto [it, inserted] = first_with_id.emplace(discs[i].id, i);
        if (!inserted)
            d.error(sources[i].id_where,
                    sources[i].id_path + ": id '" + discs[i].id +
                        "' is already used by the disc on line " +
                        std::to_string(sources[it->second].id_where.line));
    }

    std::vector<Circle> circles;
    std::vector<bool> include;
    circles.reserve(discs.size());
    include.reserve(discs.size());
    for (std::size_t i = 0; i < discs.size(); ++i) {
        circles.push_back({discs[i].position, discs[i].radius, discs[i].is_static});
        include.push_back(sources[i].usable);
    }
    // A shape's circle is only its bound: for a pair with a shape the outlines decide, and a
    // pair clear by its outlines does not hide a later overlap of the same body.
    // Bodies a joint joins (without `collide`) never collide, and may start overlapping: a
    // chain's links overlap at their pins; so may bodies that do not meet.
    std::vector<std::pair<std::size_t, std::size_t>> joined;
    for (const physics::JointDef& j : loader.scene.joints) {
        if (j.a && j.b && !j.collide) joined.emplace_back(std::min(*j.a, *j.b), std::max(*j.a, *j.b));
    }
    std::sort(joined.begin(), joined.end());
    const auto confirm = [&](std::size_t later, std::size_t earlier) {
        const Body& a = discs[later];
        const Body& b = discs[earlier];
        if (std::binary_search(joined.begin(), joined.end(),
                               std::pair{std::min(later, earlier), std::max(later, earlier)})) {
            return false;
        }
        // Nor do a sensor and what it watches, or bodies whose categories exclude each other.
        if (a.sensor || b.sensor || (a.category & b.collides) == 0 ||
            (b.category & a.collides) == 0) {
            return false;
        }
        if (!a.shape && !b.shape) return true;
        // Touching is allowed: a stack's boxes start face to face.
        return shape_overlap(a, b) > 1e-9 * std::max(a.radius, b.radius);
    };
    for (const auto& [later, earlier] : find_overlaps(circles, include, confirm)) {
        if (d.full()) break;
        const Body& a = discs[later];
        const Body& b = discs[earlier];
        const double dx = a.position.x - b.position.x, dy = a.position.y - b.position.y;
        const double depth = a.shape || b.shape
                                 ? shape_overlap(a, b)
                                 : a.radius + b.radius - std::sqrt(dx * dx + dy * dy);
        const std::string kind_a = a.shape ? "body" : "disc", kind_b = b.shape ? "body" : "disc";
        d.error(sources[later].entry,
                sources[later].where + ": " + kind_a + " '" + a.id + "' overlaps " + kind_b + " '" + b.id +
                    "' (line " + std::to_string(sources[earlier].entry.line) + ") by " +
                    format_short(depth) + " m at t = 0");
    }
    check_radii_against_reach(loader);
}

}  // namespace discreel::scene::detail
