// Overrides are parsed as YAML of their own, all in one text whose lines start past the file's
// last line: every reader then reports them at a line that Diagnostics maps back to the
// option, without a second way of locating problems.
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

// The value as YAML of its own: what cannot be on a command line made explicit. Nothing reads
// as the empty text (YAML's null has no place to report it at; an empty text has), and a
// colour as text (YAML would take its '#' for a comment).
std::string value_text(const Override& o) {
    const auto first = o.value.find_first_not_of(" \t");
    if (first == std::string::npos) return "''";
    if (o.value[first] == '#') return single_quoted(o.value);
    return o.value;
}

int lines_in(const std::string& text) {
    return 1 + static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

struct Parsed {
    std::vector<YAML::Node> keys;   // one per segment of the path
    YAML::Node value;
};

// The child of `map` under `key`'s name, or an invalid node.
YAML::Node child_of(const YAML::Node& map, const std::string& key) {
    for (const auto& entry : map) {
        if (entry.first.IsScalar() && entry.first.Scalar() == key) return entry.second;
    }
    return YAML::Node(YAML::NodeType::Undefined);
}

// Puts `parsed` at the path `segments` into `document`.
void apply_one(YAML::Node& document, const std::vector<std::string>& segments, Parsed* parsed,
               Location where, Diagnostics& d) {
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
    // Every override takes a block of lines past the file's end: its path as a flow list of
    // keys on the first, its value (continuation lines indented) after. One YAML parse of them
    // all, however many there are, so the cost is the file's lines once plus the overrides.
    struct Block {
        std::vector<std::string> segments;
        std::string value;
        int line = 0;         // 1-based, of the keys
        bool usable = true;   // its path and value passed the checks of their own
    };
    std::vector<Block> blocks;
    int line = first_line;
    std::string text(static_cast<std::size_t>(std::max(first_line - 1, 0)), '\n');
    for (const Override& o : overrides) {
        Block b{split_path(o.path), value_text(o), line, true};
        diagnostics.add_source(line, o.label);
        const Location where{line, 1};
        for (const std::string& segment : b.segments) {
            if (segment.empty() && b.usable) {
                diagnostics.error(where, "the key '" + o.path + "' has an empty part; write a "
                                         "dotted path such as physics.seed or discs.0.radius");
                b.usable = false;
            }
        }
        if (b.usable) {
            try {
                (void)YAML::Load(b.value);
            } catch (const YAML::Exception& e) {
                diagnostics.error(where, "invalid YAML in the value: " + e.msg);
                b.usable = false;
            }
        }
        if (b.usable) {
            text += "- [";
            for (std::size_t k = 0; k < b.segments.size(); ++k) {
                if (k > 0) text += ", ";
                text += single_quoted(b.segments[k]);
            }
            text += "]\n- ";
            for (const char c : b.value) {
                text += c;
                if (c == '\n') text += "  ";
            }
            text += '\n';
        } else {
            const int lines = 1 + lines_in(b.value);
            text.append(static_cast<std::size_t>(lines), '\n');
        }
        line += 1 + lines_in(b.value);
        blocks.push_back(std::move(b));
    }
    YAML::Node all;
    try {
        all = YAML::Load(text);
    } catch (const YAML::Exception& e) {
        // Each value parsed on its own; together they still may not (a value that ends a
        // block it did not open): the whole set is refused, at the first.
        diagnostics.error(Location{first_line, 1}, "invalid YAML in the values: " + e.msg);
        return;
    }
    std::size_t item = 0;
    for (std::size_t k = 0; k < blocks.size(); ++k) {
        if (!blocks[k].usable) continue;
        Parsed parsed;
        for (const YAML::Node& key : all[item]) parsed.keys.push_back(key);
        parsed.value = all[item + 1];
        item += 2;
        apply_one(document, blocks[k].segments, &parsed, Location{blocks[k].line, 1},
                  diagnostics);
    }
}

}  // namespace detail
}  // namespace discreel::scene
