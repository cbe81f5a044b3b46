#include "yaml_values.hpp"

#include <charconv>
#include <cmath>
#include <system_error>

#include "color.hpp"
#include "discreel/did_you_mean.hpp"

namespace discreel::scene::detail {
namespace {

// A quoted scalar ("3") is text even when it looks like a number; yaml-cpp tags it "!". So is
// one tagged as a string (!!str 3), which YAML's own rules make text.
bool is_quoted(const YAML::Node& node) {
    return node.Tag() == "!" || node.Tag() == "tag:yaml.org,2002:str";
}

std::string_view without_plus(std::string_view text) {
    return (!text.empty() && text[0] == '+') ? text.substr(1) : text;
}

bool is_yaml_infinity_or_nan(std::string_view text) {
    if (!text.empty() && (text[0] == '+' || text[0] == '-')) text.remove_prefix(1);
    return text == ".inf" || text == ".Inf" || text == ".INF" || text == ".nan" ||
           text == ".NaN" || text == ".NAN";
}

enum class Parsed { ok, not_a_number, out_of_range };

Parsed parse_double(std::string_view text, double& out) {
    text = without_plus(text);
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
    if (ec == std::errc::result_out_of_range) return Parsed::out_of_range;
    if (ec != std::errc() || end != text.data() + text.size()) return Parsed::not_a_number;
    return Parsed::ok;
}

template <class Int>
Parsed parse_int(std::string_view text, Int& out) {
    text = without_plus(text);
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
    if (ec == std::errc::result_out_of_range) return Parsed::out_of_range;
    if (ec != std::errc() || end != text.data() + text.size()) return Parsed::not_a_number;
    return Parsed::ok;
}

void expected(const Value& value, std::string_view what, Diagnostics& diagnostics) {
    diagnostics.error(value.where, value.path + ": expected " + std::string(what) + ", got " +
                                       describe(value.node));
}

// Shared by the number readers: explains quoted numbers and non-finite values.
bool explain_non_number(const Value& value, std::string_view what, Diagnostics& diagnostics) {
    if (!value.node.IsScalar()) {
        expected(value, what, diagnostics);
        return true;
    }
    const std::string& text = value.node.Scalar();
    double number = 0;
    if (is_quoted(value.node) && parse_double(text, number) == Parsed::ok) {
        const bool tagged = value.node.Tag() != "!";
        diagnostics.error(value.where, value.path + ": expected " + std::string(what) +
                                           (tagged ? ", got the text " : ", got the quoted text ") +
                                           describe(value.node) +
                                           (tagged ? " (tagged !!str); remove the tag"
                                                   : "; remove the quotes"));
        return true;
    }
    if (!is_quoted(value.node) &&
        (is_yaml_infinity_or_nan(text) ||
         (parse_double(text, number) == Parsed::ok && !std::isfinite(number)))) {
        diagnostics.error(value.where,
                          value.path + ": must be a finite number, got " + describe(value.node));
        return true;
    }
    return false;
}

}  // namespace

Location location_of(const YAML::Node& node, Location fallback) {
    const YAML::Mark mark = node.Mark();
    if (mark.is_null() || mark.line < 0 || mark.column < 0) return fallback;
    return {mark.line + 1, mark.column + 1};
}

std::string describe(const YAML::Node& node) {
    switch (node.Type()) {
        case YAML::NodeType::Scalar: {
            const std::string& text = node.Scalar();
            if (text.size() > 40) return "'" + text.substr(0, 37) + "...'";
            return "'" + text + "'";
        }
        case YAML::NodeType::Sequence:
            if (node.size() == 0) return "an empty list";
            if (node.size() == 1) return "a list of 1 item";
            return "a list of " + std::to_string(node.size()) + " items";
        case YAML::NodeType::Map:
            return "a mapping";
        case YAML::NodeType::Null:
        case YAML::NodeType::Undefined:
            break;
    }
    return "nothing";
}

std::optional<Fields> Fields::open(const Value& map, std::span<const std::string_view> known,
                                   Diagnostics& diagnostics) {
    Fields fields;
    fields.where_ = map.where;
    fields.path_ = map.path;
    if (map.is_null()) return fields;
    if (!map.node.IsMap()) {
        expected(map, "a mapping (key: value pairs)", diagnostics);
        return std::nullopt;
    }
    const std::string context = map.path.empty() ? "" : map.path + ": ";
    const std::string unknown = map.path.empty() ? "unknown top-level key " : "unknown key ";
    for (auto it = map.node.begin(); it != map.node.end() && !diagnostics.full(); ++it) {
        // Copies, not references: the iterator's `->` hands out a temporary pair.
        const YAML::Node key = it->first;
        const YAML::Node item = it->second;
        const Location key_where = location_of(key, map.where);
        if (!key.IsScalar()) {
            diagnostics.error(key_where,
                              context + "keys must be plain names, got " + describe(key));
            continue;
        }
        const std::string& name = key.Scalar();
        if (const Entry* first = fields.find(name)) {
            diagnostics.error(key_where, context + "key '" + name + "' is given twice (first on line " +
                                             std::to_string(first->key_where.line) + ")");
            continue;
        }
        bool is_known = false;
        for (std::string_view k : known) is_known = is_known || k == name;
        if (!is_known) {
            std::string message = context + unknown + "'" + name + "'";
            if (const auto suggestion = closest_match(name, known)) {
                message += "; did you mean '" + *suggestion + "'?";
            } else {
                message += "; expected one of: ";
                for (std::size_t i = 0; i < known.size(); ++i)
                    message += (i ? ", " : "") + std::string(known[i]);
            }
            diagnostics.error(key_where, std::move(message));
            continue;
        }
        const std::string path = map.path.empty() ? name : map.path + "." + name;
        // An empty value's mark points at whatever follows it; its key is the better place.
        const Location where = item.IsNull() ? key_where : location_of(item, key_where);
        fields.entries_.push_back({name, key_where, Value{item, where, path}});
    }
    return fields;
}

const Fields::Entry* Fields::find(std::string_view key) const {
    for (const Entry& e : entries_)
        if (e.key == key) return &e;
    return nullptr;
}

std::optional<Value> Fields::get(std::string_view key) const {
    if (const Entry* e = find(key)) return e->value;
    return std::nullopt;
}

Location Fields::key_location(std::string_view key) const {
    const Entry* e = find(key);
    return e ? e->key_where : where_;
}

void Fields::adopt(const Fields& inner, std::span<const std::string_view> keys,
                   Diagnostics& diagnostics) {
    const std::string inner_name = inner.path().substr(inner.path().rfind('.') + 1);
    for (const std::string_view key : keys) {
        const Entry* entry = inner.find(key);
        if (!entry) continue;
        if (const Entry* outer = find(key)) {
            diagnostics.error(entry->key_where,
                              inner.path() + ": '" + entry->key + "' is given both here and beside '" +
                                  inner_name + ":' on line " +
                                  std::to_string(outer->key_where.line) + "; give it once");
            continue;
        }
        entries_.push_back(*entry);
    }
}

std::string_view Fields::later_of(std::string_view a, std::string_view b) const {
    const Location la = key_location(a), lb = key_location(b);
    const bool a_later = la.line != lb.line ? la.line > lb.line : la.column > lb.column;
    return a_later ? a : b;
}

std::optional<std::vector<Value>> read_list(const Value& value, Diagnostics& diagnostics) {
    std::vector<Value> items;
    if (value.is_null()) return items;
    if (!value.node.IsSequence()) {
        expected(value, "a list (items starting with '- ')", diagnostics);
        return std::nullopt;
    }
    items.reserve(value.node.size());
    std::size_t i = 0;
    for (auto it = value.node.begin(); it != value.node.end(); ++it, ++i) {
        const YAML::Node item = *it;
        // An empty item's mark points past it; the list's own position is the honest fallback.
        const Location where = item.IsNull() ? value.where : location_of(item, value.where);
        items.emplace_back(item, where, value.path + "[" + std::to_string(i) + "]");
    }
    return items;
}

std::optional<std::vector<Value>> read_tuple(const Value& value, std::size_t size,
                                             std::string_view shape, Diagnostics& diagnostics) {
    const std::string numbers = size == 2 ? "two" : size == 3 ? "three" : std::to_string(size);
    if (!value.node.IsSequence() || value.node.size() != size) {
        expected(value, "a list of " + numbers + " numbers " + std::string(shape), diagnostics);
        return std::nullopt;
    }
    return read_list(value, diagnostics);
}

std::optional<double> read_number(const Value& value, Diagnostics& diagnostics) {
    if (explain_non_number(value, "a number", diagnostics)) return std::nullopt;
    double number = 0;
    const Parsed parsed = is_quoted(value.node) ? Parsed::not_a_number
                                                : parse_double(value.node.Scalar(), number);
    if (parsed == Parsed::out_of_range) {
        diagnostics.error(value.where, value.path + ": the number " + describe(value.node) +
                                           " is too large or too small to use");
        return std::nullopt;
    }
    if (parsed != Parsed::ok) {
        expected(value, "a number", diagnostics);
        return std::nullopt;
    }
    // Nothing a scene describes needs more, and squares of these (energies, distances) stay
    // far from overflowing a double.
    if (std::abs(number) > max_scene_number) {
        diagnostics.error(value.where, value.path + ": " + format_number(number) +
                                           " is out of range; numbers in a scene lie within -" +
                                           format_number(max_scene_number) + ".." +
                                           format_number(max_scene_number));
        return std::nullopt;
    }
    return number;
}

namespace {

template <class Int>
std::optional<Int> read_whole(const Value& value, Diagnostics& diagnostics) {
    if (explain_non_number(value, "a whole number", diagnostics)) return std::nullopt;
    Int number = 0;
    const std::string& text = value.node.Scalar();
    const Parsed parsed = is_quoted(value.node) ? Parsed::not_a_number : parse_int(text, number);
    if (parsed == Parsed::ok) return number;
    if (parsed == Parsed::out_of_range) {
        diagnostics.error(value.where,
                          value.path + ": the number " + describe(value.node) + " is too large");
        return std::nullopt;
    }
    expected(value, "a whole number", diagnostics);
    return std::nullopt;
}

}  // namespace

std::optional<long long> read_integer(const Value& value, Diagnostics& diagnostics) {
    return read_whole<long long>(value, diagnostics);
}

std::optional<std::uint64_t> read_unsigned(const Value& value, Diagnostics& diagnostics) {
    if (value.node.IsScalar() && !value.node.Scalar().empty() && value.node.Scalar()[0] == '-' &&
        !is_quoted(value.node)) {
        long long negative = 0;
        if (parse_int(value.node.Scalar(), negative) == Parsed::ok) {
            diagnostics.error(value.where,
                              value.path + ": must be at least 0, got " + value.node.Scalar());
            return std::nullopt;
        }
    }
    return read_whole<std::uint64_t>(value, diagnostics);
}

std::optional<bool> read_bool(const Value& value, Diagnostics& diagnostics) {
    if (value.node.IsScalar() && !is_quoted(value.node)) {
        const std::string& text = value.node.Scalar();
        if (text == "true" || text == "True" || text == "TRUE") return true;
        if (text == "false" || text == "False" || text == "FALSE") return false;
    }
    expected(value, "true or false", diagnostics);
    return std::nullopt;
}

std::optional<std::size_t> read_choice(const Value& value,
                                       std::span<const std::string_view> choices,
                                       Diagnostics& diagnostics) {
    if (value.node.IsScalar())
        for (std::size_t i = 0; i < choices.size(); ++i)
            if (value.node.Scalar() == choices[i]) return i;
    std::string what = "one of ";
    for (std::size_t i = 0; i < choices.size(); ++i)
        what += (i == 0 ? "" : ", ") + std::string(choices[i]);
    expected(value, what, diagnostics);
    return std::nullopt;
}

std::optional<Color> read_color(const Value& value, Diagnostics& diagnostics) {
    constexpr std::string_view what =
        "a colour like \"#rrggbb\", \"#rrggbbaa\", \"#rgb\" or a CSS name (\"steelblue\")";
    if (value.is_null()) {
        // `color: #8899aa` without quotes: YAML reads everything from '#' on as a comment.
        diagnostics.error(value.where,
                          value.path + ": expected " + std::string(what) +
                              ", got nothing (put the colour in quotes: YAML reads an unquoted "
                              "'#' as the start of a comment)");
        return std::nullopt;
    }
    if (value.node.IsScalar()) {
        const std::string& text = value.node.Scalar();
        if (const auto color = parse_color(text)) return color;
        // A word that is no colour name: the closest name, if it looks like a typo.
        if (!text.empty() && text[0] != '#') {
            if (const auto name = closest_match(text, color_names())) {
                diagnostics.error(value.where, value.path + ": '" + text +
                                                   "' is not a colour name; did you mean '" +
                                                   *name + "'?");
                return std::nullopt;
            }
        }
    }
    expected(value, what, diagnostics);
    return std::nullopt;
}

std::optional<Vec2> read_vec2(const Value& value, std::string_view shape,
                              Diagnostics& diagnostics) {
    const auto items = read_tuple(value, 2, shape, diagnostics);
    if (!items) return std::nullopt;
    const auto x = read_number((*items)[0], diagnostics);
    const auto y = read_number((*items)[1], diagnostics);
    if (!x || !y) return std::nullopt;
    return Vec2{*x, *y};
}

std::optional<Corners> read_corners(const Value& value, std::string_view shape,
                                    Diagnostics& diagnostics) {
    const bool two_lists = value.node.IsSequence() && value.node.size() == 2 &&
                           value.node[0].IsSequence() && value.node[1].IsSequence();
    if (!two_lists) {
        expected(value, "two points " + std::string(shape), diagnostics);
        return std::nullopt;
    }
    const auto items = read_list(value, diagnostics);
    const auto a = read_vec2((*items)[0], "[x, y]", diagnostics);
    const auto b = read_vec2((*items)[1], "[x, y]", diagnostics);
    if (!a || !b) return std::nullopt;
    return Corners{*a, *b};
}

bool check_between(const Value& value, double v, double lo, double hi, Diagnostics& diagnostics) {
    if (v >= lo && v <= hi) return true;
    diagnostics.error(value.where, value.path + ": must be between " + format_number(lo) +
                                       " and " + format_number(hi) + ", got " + format_number(v));
    return false;
}

bool check_positive(const Value& value, double v, Diagnostics& diagnostics) {
    if (v > 0) return true;
    diagnostics.error(value.where,
                      value.path + ": must be greater than 0, got " + format_number(v));
    return false;
}

bool check_non_negative(const Value& value, double v, Diagnostics& diagnostics) {
    if (v >= 0) return true;
    diagnostics.error(value.where, value.path + ": must be at least 0, got " + format_number(v));
    return false;
}

std::optional<double> read_positive(const Value& value, Diagnostics& diagnostics) {
    const auto v = read_number(value, diagnostics);
    if (!v || !check_positive(value, *v, diagnostics)) return std::nullopt;
    return v;
}

std::optional<double> read_non_negative(const Value& value, Diagnostics& diagnostics) {
    const auto v = read_number(value, diagnostics);
    if (!v || !check_non_negative(value, *v, diagnostics)) return std::nullopt;
    return v;
}

std::optional<double> read_between(const Value& value, double lo, double hi,
                                   Diagnostics& diagnostics) {
    const auto v = read_number(value, diagnostics);
    if (!v || !check_between(value, *v, lo, hi, diagnostics)) return std::nullopt;
    return v;
}

}  // namespace discreel::scene::detail
