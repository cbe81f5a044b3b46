// `overlays:` (titles, captions, readouts on screen) and bodies' `label:`: text with live
// values, {t} or {speed:cue:.1}, checked here against the scene's bodies.
#include <array>
#include <string>
#include <string_view>

#include "disc_ref.hpp"
#include "discreel/did_you_mean.hpp"
#include "loader.hpp"

namespace discreel::scene::detail {
namespace {

constexpr double max_text_size = 1000;   // metres or frame heights: beyond, nothing is readable
constexpr std::size_t max_text_length = 1000;   // characters of one overlay or label
constexpr std::size_t max_overlays = 1000;

constexpr std::array<std::string_view, 9> readout_names{
    "t", "frame", "energy", "kinetic", "momentum", "speed", "x", "y", "angle"};
constexpr std::array<std::string_view, 9> anchor_names{
    "top-left", "top", "top-right", "left", "center", "right", "bottom-left", "bottom",
    "bottom-right"};

bool needs_body(Readout::Kind kind) { return kind >= Readout::Kind::speed; }

// One readout's inside, "speed:cue:.1": its name, a body for the per-body ones, a precision.
std::optional<Readout> read_readout(Loader& loader, const Value& value, std::string_view inside,
                                    const DiscIds& ids) {
    auto& d = loader.diagnostics;
    std::vector<std::string_view> fields;
    for (std::size_t start = 0;;) {
        const std::size_t colon = inside.find(':', start);
        fields.push_back(inside.substr(start, colon - start));
        if (colon == std::string_view::npos) break;
        start = colon + 1;
    }
    std::string braced(1, '{');
    braced.append(inside);
    braced.push_back('}');
    const auto* name = std::find(readout_names.begin(), readout_names.end(), fields[0]);
    if (name == readout_names.end()) {
        std::string message = value.path + ": unknown readout '" + braced + "'";
        if (const auto close = closest_match(fields[0], readout_names)) {
            message += "; did you mean '{" + *close + "}'?";
        } else {
            message += "; readouts are {t}, {frame}, {energy}, {kinetic}, {momentum}, "
                       "{speed:ID}, {x:ID}, {y:ID}, {angle:ID}";
        }
        d.error(value.where, message);
        return std::nullopt;
    }
    Readout r;
    r.kind = static_cast<Readout::Kind>(name - readout_names.begin());
    std::size_t next = 1;
    if (needs_body(r.kind)) {
        if (fields.size() < 2 || fields[1].empty() || fields[1][0] == '.') {
            d.error(value.where, value.path + ": the readout '" + braced +
                                     "' needs a body: {" + std::string(fields[0]) + ":ID}");
            return std::nullopt;
        }
        const auto it = ids.by_id.find(std::string(fields[1]));
        if (it == ids.by_id.end()) {
            std::string message = value.path + ": the readout '" + braced +
                                  "' names no body: no body has id '" + std::string(fields[1]) +
                                  "'";
            if (const auto close = closest_match(fields[1], ids.names)) {
                message += "; did you mean '" + *close + "'?";
            }
            d.error(value.where, message);
            return std::nullopt;
        }
        r.body = it->second;
        next = 2;
    }
    if (fields.size() > next) {
        const std::string_view p = fields[next];
        if (fields.size() > next + 1 || p.size() != 2 || p[0] != '.' || p[1] < '0' || p[1] > '9') {
            d.error(value.where, value.path + ": the readout '" + braced +
                                     "' ends in a precision like ':.2' (0 to 9 digits after "
                                     "the point)");
            return std::nullopt;
        }
        r.precision = p[1] - '0';
    }
    return r;
}

}  // namespace

std::optional<std::vector<TextPart>> read_text(Loader& loader, const Value& value) {
    auto& d = loader.diagnostics;
    if (!value.node.IsScalar() || value.is_null()) {
        d.error(value.where, value.path + ": expected text, got " + describe(value.node));
        return std::nullopt;
    }
    const std::string& text = value.node.Scalar();
    if (text.size() > max_text_length) {
        d.error(value.where, value.path + ": text of " + std::to_string(text.size()) +
                                 " characters; the limit is " + std::to_string(max_text_length));
        return std::nullopt;
    }
    const DiscIds ids(loader.scene.bodies);
    std::vector<TextPart> parts(1);
    bool ok = true;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        // "{{" and "}}" are braces themselves.
        if ((c == '{' || c == '}') && i + 1 < text.size() && text[i + 1] == c) {
            parts.back().literal += c;
            ++i;
            continue;
        }
        if (c == '}') {
            d.error(value.where, value.path + ": a '}' without its '{' (write '}}' for a brace)");
            return std::nullopt;
        }
        if (c != '{') {
            parts.back().literal += c;
            continue;
        }
        const std::size_t close = text.find('}', i);
        if (close == std::string::npos) {
            d.error(value.where, value.path + ": a '{' without its '}' (write '{{' for a brace)");
            return std::nullopt;
        }
        const auto readout =
            read_readout(loader, value, std::string_view(text).substr(i + 1, close - i - 1), ids);
        ok = ok && readout;
        if (readout) parts.push_back({"", readout});
        parts.emplace_back();
        i = close;
    }
    if (!ok) return std::nullopt;
    return parts;
}

void read_overlays(Loader& loader, const Value& value) {
    static constexpr std::array<std::string_view, 8> known{"text", "at",    "anchor", "size",
                                                           "color", "from", "to",     "fade"};
    auto& d = loader.diagnostics;
    const auto items = read_list(value, d);
    if (!items) return;
    if (items->size() > max_overlays) {
        d.error(value.where, value.path + ": too many overlays (" +
                                 std::to_string(items->size()) + "); the limit is " +
                                 std::to_string(max_overlays));
        return;
    }
    for (const Value& item : *items) {
        const auto fields = Fields::open(item, known, d);
        if (!fields) continue;
        Overlay o;
        bool ok = true;
        if (const auto text = fields->get("text")) {
            const auto parts = read_text(loader, *text);
            ok = ok && parts;
            if (parts) o.text = *parts;
        } else {
            d.error(item.where, item.path + ": missing required key 'text'");
            ok = false;
        }
        if (const auto at = fields->get("at")) {
            o.at = read_vec2(*at, "[x, y]", d);
            ok = ok && o.at;
            o.anchor = TextAnchor::left;
            o.size = 0.3;
        }
        if (const auto anchor = fields->get("anchor")) {
            const auto i = read_choice(*anchor, anchor_names, d);
            ok = ok && i;
            if (i) o.anchor = static_cast<TextAnchor>(*i);
        }
        if (const auto size = fields->get("size")) {
            const auto v = read_positive(*size, d);
            if (v && *v > max_text_size) {
                d.error(size->where, size->path + ": at most " + format_number(max_text_size) +
                                         ", got " + format_number(*v));
                ok = false;
            }
            ok = ok && v;
            o.size = v.value_or(o.size);
        }
        if (const auto color = fields->get("color")) {
            const auto c = read_color(*color, d);
            ok = ok && c;
            if (c) o.color = *c;
        }
        if (const auto from = fields->get("from")) {
            const auto v = read_non_negative(*from, d);
            ok = ok && v;
            o.from = v.value_or(0);
        }
        if (const auto to = fields->get("to")) {
            o.to = read_non_negative(*to, d);
            ok = ok && o.to;
            if (o.to && *o.to <= o.from) {
                d.error(to->where, to->path + ": 'to' (" + format_number(*o.to) +
                                       " s) must come after 'from' (" + format_number(o.from) +
                                       " s)");
                ok = false;
            }
        }
        if (const auto fade = fields->get("fade")) {
            const auto v = read_non_negative(*fade, d);
            ok = ok && v;
            o.fade = v.value_or(0);
        }
        if (ok) loader.scene.overlays.push_back(std::move(o));
    }
}

void read_labels(Loader& loader) {
    auto& d = loader.diagnostics;
    for (const Loader::Label& label : loader.labels) {
        if (label.body >= loader.scene.bodies.size()) continue;
        Body& body = loader.scene.bodies[label.body];
        if (label.turns) {
            if (!label.text) {
                d.error(label.turns->where, label.where + ": 'label_turns' needs a 'label'");
            } else if (const auto turns = read_bool(*label.turns, d)) {
                body.label_turns = *turns;
            }
        }
        if (!label.text) continue;
        if (const auto parts = read_text(loader, *label.text)) body.label = *parts;
    }
}

}  // namespace discreel::scene::detail
