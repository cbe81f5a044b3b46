#pragma once
// What `discs:` and `bodies:` entries share: the per-body keys, ids, the limit on bodies, how a
// body joins the scene, and the readers of ranges and colour lists.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "loader.hpp"
#include "yaml_values.hpp"

namespace discreel::scene::detail {

// The per-body keys of an entry: a single body's own, or what a generator gives every body.
struct Properties {
    Vec2 velocity;
    double angle = 0;
    double angular_velocity = 0;
    std::optional<double> mass;       // kg
    double density = 1;               // kg/m^2, used when mass is not given
    double restitution = 0.8;
    double friction = 0.2;
    std::optional<Color> color;       // none: from the palette by body index
    bool is_static = false;
    std::optional<physics::KinematicDef> kinematic;   // single entries only
    std::uint32_t category = physics::default_category;   // bits (categories.cpp)
    std::uint32_t collides = physics::all_categories;
    bool sensor = false;
};

// A category name's bit (categories.cpp), given the next free one when first named; nothing
// when the name is not valid or a 33rd.
std::optional<std::uint32_t> category_bit(Loader& loader, const Value& value);
// `category` and `collides` of an entry into the bits; false on a problem (reported).
bool read_filter(Loader& loader, const Fields& fields, std::uint32_t& category,
                 std::uint32_t& collides);

// A `kinematic:` mapping; nothing when it has problems (each reported).
std::optional<physics::KinematicDef> read_kinematic(const Value& value, Diagnostics& d);

Properties read_properties(Loader& loader, const Fields& fields, const Value& item);
std::optional<std::string> read_id(const Value& value, Diagnostics& d);
// A disc of `radius`, its mass from the properties (mass, or density * pi r^2).
Body make_disc(const Properties& p, std::string id, Vec2 position, double radius,
               std::size_t index);
// The moment of inertia physics gives the body (physics::inertia_of), kg m^2; 0 for a static
// body, which never turns. The trace writes it, so it must be physics' own number.
double inertia_of(const Body& body);
// The mass must come out positive and finite; reports the entry otherwise.
bool check_mass(const Body& disc, const Value& item, Diagnostics& d);
// Whether `count` more bodies still fit under the limit; reports the entry that breaks it.
bool room_for(Loader& loader, const Value& item, std::size_t count);
void add_disc(Loader& loader, Body disc, const Value& item, const std::optional<Value>& id_value,
              const std::optional<Value>& velocity_value, bool usable);
// What names and places a single body: its id (written, or its index) and its required
// position (reported when missing).
struct Placement {
    std::string id;
    std::optional<Value> id_value;
    std::optional<Vec2> position;
};
Placement read_placement(Loader& loader, const Fields& fields, const Value& item);

std::optional<std::vector<Color>> read_colors(const Value& value, Diagnostics& d);
std::optional<Value> required(const Fields& fields, std::string_view key, Diagnostics& d);

// A number (min = max) or a range [min, max]; each end checked by `check`.
struct Range {
    double min = 0, max = 0;
};
template <class Check>
std::optional<Range> read_range(const Value& value, Check check, Diagnostics& d) {
    if (value.node.IsScalar()) {
        const auto v = read_number(value, d);
        if (!v || !check(value, *v, d)) return std::nullopt;
        return Range{*v, *v};
    }
    if (!value.node.IsSequence() || value.node.size() != 2) {
        d.error(value.where, value.path + ": expected a number or a range [min, max], got " +
                                 describe(value.node));
        return std::nullopt;
    }
    const auto items = read_list(value, d);
    const auto lo = read_number((*items)[0], d);
    const auto hi = read_number((*items)[1], d);
    const bool lo_ok = lo && check((*items)[0], *lo, d);
    const bool hi_ok = hi && check((*items)[1], *hi, d);
    if (!lo_ok || !hi_ok) return std::nullopt;
    if (*lo > *hi) {
        d.error(value.where, value.path + ": the minimum " + format_number(*lo) +
                                 " is larger than the maximum " + format_number(*hi));
        return std::nullopt;
    }
    return Range{*lo, *hi};
}


}  // namespace discreel::scene::detail
