// Overrides are parsed as YAML of their own, preceded by enough blank lines that their marks
// fall past the file's last line: every reader then reports them at a line that Diagnostics
// maps back to the option, without a second way of locating problems.
#include "overrides.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "discreel/parse_number.hpp"

namespace discreel::scene {

Expected<Override> parse_override(std::string_view text, std::string_view option) {
    const std::string label = std::string(option) + " " + std::string(text);
    const auto equals = text.find('=');
    if (equals == std::string_view::npos || equals == 0) {
        return Error{label + ": expected KEY=VALUE with KEY a dotted path into the scene, "
                             "e.g. physics.seed=3 or discs.0.radius=0.3"};
    }
    return Override{std::string(text.substr(0, equals)), std::string(text.substr(equals + 1)),
                    label};
}

namespace detail {
namespace {

std::vector<std::string> split_path(const std::string& path) {
    std::vector<std::string> out(1);
    for (const char c : path) {
        if (c == '.') {
            out.emplace_back();
        } else {
            out.back() += c;
        }
    }
    return out;
}

std::string single_quoted(const std::string& text) {
    std::string out = "'";
    for (const char c : text) {
        out += c;
        if (c == '\'') out += '\'';
    }
    return out + "'";
}

// Lines an override's text spans.
int lines_of(const Override& o) {
    return 1 + static_cast<int>(std::count(o.path.begin(), o.path.end(), '\n') +
                                std::count(o.value.begin(), o.value.end(), '\n'));
}

struct Parsed {
    std::vector<YAML::Node> keys;   // one per segment of the path
    YAML::Node value;
};

// The path's segments and the value, as nodes whose marks are on 0-based line `line`.
std::optional<Parsed> parse_at(const Override& o, const std::vector<std::string>& segments,
                               int line, Location where, Diagnostics& d) {
    const std::string blank(static_cast<std::size_t>(line), '\n');
    std::string keys = blank + "[";
    for (std::size_t k = 0; k < segments.size(); ++k) {
        if (k > 0) keys += ", ";
        keys += single_quoted(segments[k]);
    }
    keys += "]";
    // What cannot be YAML of its own on a command line: nothing (YAML's null has no place to
    // report it at; an empty text has), and a colour, which YAML would take for a comment.
    std::string value = o.value;
    const auto first = value.find_first_not_of(" \t");
    if (first == std::string::npos) {
        value = "''";
    } else if (value[first] == '#') {
        value = single_quoted(value);
    }
    Parsed parsed;
    try {
        const YAML::Node list = YAML::Load(keys);
        for (const YAML::Node& key : list) parsed.keys.push_back(key);
        parsed.value = YAML::Load(blank + value);
    } catch (const YAML::Exception& e) {
        d.error(where, "invalid YAML in the value: " + e.msg);
        return std::nullopt;
    }
    return parsed;
}

// The child of `map` under `key`'s name, or an invalid node.
YAML::Node child_of(const YAML::Node& map, const std::string& key) {
    for (const auto& entry : map) {
        if (entry.first.IsScalar() && entry.first.Scalar() == key) return entry.second;
    }
    return YAML::Node(YAML::NodeType::Undefined);
}

void apply_one(YAML::Node& document, const Override& o, int line, Diagnostics& d) {
    const Location where{line + 1, 1};
    const std::vector<std::string> segments = split_path(o.path);
    for (const std::string& segment : segments) {
        if (segment.empty()) {
            d.error(where, "the key '" + o.path + "' has an empty part; write a dotted path "
                           "such as physics.seed or discs.0.radius");
            return;
        }
    }
    auto parsed = parse_at(o, segments, line, where, d);
    if (!parsed) return;
    YAML::Node node;
    node.reset(document);
    std::string walked;   // the path so far, for messages
    for (std::size_t k = 0; k < segments.size(); ++k) {
        const std::string& segment = segments[k];
        const bool last = k + 1 == segments.size();
        const std::string here = walked.empty() ? "the scene" : "'" + walked + "'";
        YAML::Node next(YAML::NodeType::Undefined);
        if (node.IsSequence()) {
            const auto index = parse_whole<std::size_t>(segment);
            if (!index || *index >= node.size()) {
                d.error(where, here + " is a list of " + std::to_string(node.size()) +
                                   " items, numbered from 0; it has no item '" + segment + "'");
                return;
            }
            next.reset(node[*index]);
        } else if (node.IsMap() || node.IsNull()) {
            if (node.IsMap()) next.reset(child_of(node, segment));
            if (!next.IsDefined()) {
                YAML::Node created = last ? parsed->value : YAML::Node(YAML::NodeType::Map);
                node.force_insert(parsed->keys[k], created);
                next.reset(created);
                if (last) return;
            }
        } else {
            d.error(where, here + " is a single value, not a mapping or a list: it has no '" +
                               segment + "'");
            return;
        }
        if (last) {
            next = parsed->value;   // writes into the scene's node
            return;
        }
        node.reset(next);
        if (!walked.empty()) walked += '.';
        walked += segment;
    }
}

}  // namespace

void apply_overrides(YAML::Node& document, std::span<const Override> overrides, int first_line,
                     Diagnostics& diagnostics) {
    int line = first_line - 1;   // 0-based, as marks are
    for (const Override& o : overrides) {
        diagnostics.add_source(line + 1, o.label);
        apply_one(document, o, line, diagnostics);
        line += lines_of(o);
    }
}

}  // namespace detail
}  // namespace discreel::scene
