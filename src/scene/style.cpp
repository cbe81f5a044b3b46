// `style:` — how frames look: disc details and the optional overlays.
#include <algorithm>
#include <array>
#include <string_view>

#include "discreel/did_you_mean.hpp"
#include "loader.hpp"

namespace discreel::scene::detail {
namespace {

constexpr double max_arrow_scale = 100;   // seconds
constexpr double min_arrow_width = 0.5, max_arrow_width = 20;   // pixels
constexpr double max_trail_length = 10;   // seconds
constexpr double max_arrow_fade = 10;     // seconds

// In (0, max]: lengths and scales that must be something, within reason.
std::optional<double> read_up_to(const Value& value, double max, Diagnostics& d) {
    const auto v = read_number(value, d);
    if (!v) return std::nullopt;
    if (*v <= 0 || *v > max) {
        d.error(value.where, value.path + ": must be greater than 0 and at most " +
                                 format_number(max) + ", got " + format_number(*v));
        return std::nullopt;
    }
    return v;
}

// An overlay is a mapping of its settings, or `true` / `false` for all defaults / off. A
// mapping turns it on unless it says `enabled: false`. Returns the mapping's fields, if any.
std::optional<Fields> open_overlay(const Value& value, std::span<const std::string_view> known,
                                   bool& enabled, Diagnostics& d) {
    Diagnostics quiet;
    if (value.node.IsScalar() && !value.is_null()) {
        if (const auto on = read_bool(value, quiet)) {
            enabled = *on;
            return std::nullopt;
        }
    }
    if (!value.is_null() && !value.node.IsMap()) {
        d.error(value.where, value.path + ": expected true, false or a mapping of settings, got " +
                                 describe(value.node));
        return std::nullopt;
    }
    auto fields = Fields::open(value, known, d);
    if (!fields) return std::nullopt;
    enabled = true;
    if (const auto e = fields->get("enabled"))
        if (const auto on = read_bool(*e, d)) enabled = *on;
    return fields;
}

void read_arrows(const Value& value, VelocityArrows& arrows, Diagnostics& d) {
    static constexpr std::array<std::string_view, 5> known{"enabled", "scale", "color", "width",
                                                           "after_contact"};
    const auto fields = open_overlay(value, known, arrows.enabled, d);
    if (!fields) return;
    if (const auto after = fields->get("after_contact"))
        if (const auto v = read_up_to(*after, max_arrow_fade, d)) arrows.after_contact = *v;
    if (const auto scale = fields->get("scale"))
        if (const auto v = read_up_to(*scale, max_arrow_scale, d)) arrows.scale = *v;
    if (const auto color = fields->get("color"))
        if (const auto c = read_color(*color, d)) arrows.color = *c;
    if (const auto width = fields->get("width"))
        if (const auto v = read_between(*width, min_arrow_width, max_arrow_width, d))
            arrows.width = *v;
}

void read_trails(const Value& value, Trails& trails, Diagnostics& d) {
    static constexpr std::array<std::string_view, 4> known{"enabled", "length", "fade", "width"};
    const auto fields = open_overlay(value, known, trails.enabled, d);
    if (!fields) return;
    if (const auto length = fields->get("length"))
        if (const auto v = read_up_to(*length, max_trail_length, d)) trails.length = *v;
    if (const auto fade = fields->get("fade"))
        if (const auto v = read_bool(*fade, d)) trails.fade = *v;
    if (const auto width = fields->get("width"))
        if (const auto v = read_up_to(*width, 1, d)) trails.width = *v;
}

void read_clock(const Value& value, Clock& clock, Diagnostics& d) {
    static constexpr std::array<std::string_view, 4> known{"enabled", "corner", "format",
                                                           "color"};
    static constexpr std::array<std::string_view, 4> corners{"top-left", "top-right",
                                                             "bottom-left", "bottom-right"};
    static constexpr std::array<std::string_view, 3> formats{"time", "frame", "both"};
    const auto fields = open_overlay(value, known, clock.enabled, d);
    if (!fields) return;
    if (const auto corner = fields->get("corner"))
        if (const auto i = read_choice(*corner, corners, d)) clock.corner = static_cast<Corner>(*i);
    if (const auto format = fields->get("format"))
        if (const auto i = read_choice(*format, formats, d))
            clock.format = static_cast<ClockFormat>(*i);
    if (const auto color = fields->get("color"))
        if (const auto c = read_color(*color, d)) clock.color = *c;
}

void read_joint_lines(const Value& value, JointLines& lines, Diagnostics& d) {
    static constexpr std::array<std::string_view, 3> known{"enabled", "color", "width"};
    const auto fields = open_overlay(value, known, lines.enabled, d);
    if (!fields) return;
    if (const auto color = fields->get("color"))
        if (const auto c = read_color(*color, d)) lines.color = *c;
    if (const auto width = fields->get("width"))
        if (const auto v = read_between(*width, min_arrow_width, max_arrow_width, d))
            lines.width = *v;
}

// `debug: [contacts, normals, ...]`: each name once, in any order.
void read_debug(const Value& value, DebugDraw& debug, Diagnostics& d) {
    static constexpr std::array<std::string_view, 6> names{"contacts", "normals", "impulses",
                                                           "boxes",    "joints",  "sleep"};
    const auto items = read_list(value, d);
    if (!items) return;
    for (const Value& item : *items) {
        const std::string word = item.node.IsScalar() ? item.node.Scalar() : std::string();
        const auto known = std::find(names.begin(), names.end(), word);
        if (!item.node.IsScalar() || known == names.end()) {
            std::string message = item.path + ": expected one of contacts, normals, impulses, "
                                              "boxes, joints, sleep, got " + describe(item.node);
            if (const auto near = closest_match(word, names)) {
                message += "; did you mean '" + *near + "'?";
            }
            d.error(item.where, message);
            continue;
        }
        const std::array<bool*, 6> flags{&debug.contacts, &debug.normals, &debug.impulses,
                                         &debug.boxes,    &debug.joints,  &debug.sleep};
        *flags[static_cast<std::size_t>(known - names.begin())] = true;
    }
}

}  // namespace

void read_style(Loader& loader, const Value& value) {
    static constexpr std::array<std::string_view, 8> known{
        "outline", "spin_marker", "velocity_arrows", "trails", "clock", "joints", "flash",
        "debug"};
    auto& d = loader.diagnostics;
    Style& style = loader.scene.style;
    const auto fields = Fields::open(value, known, d);
    if (!fields) return;
    if (const auto outline = fields->get("outline"))
        if (const auto v = read_bool(*outline, d)) style.outline = *v;
    if (const auto spin = fields->get("spin_marker"))
        if (const auto v = read_bool(*spin, d)) style.spin_marker = *v;
    if (const auto arrows = fields->get("velocity_arrows"))
        read_arrows(*arrows, style.velocity_arrows, d);
    if (const auto trails = fields->get("trails")) read_trails(*trails, style.trails, d);
    if (const auto clock = fields->get("clock")) read_clock(*clock, style.clock, d);
    if (const auto joints = fields->get("joints")) read_joint_lines(*joints, style.joints, d);
    if (const auto flash = fields->get("flash"))
        if (const auto v = read_up_to(*flash, max_arrow_fade, d)) style.flash = *v;
    if (const auto debug = fields->get("debug")) read_debug(*debug, style.debug, d);
}

}  // namespace discreel::scene::detail
