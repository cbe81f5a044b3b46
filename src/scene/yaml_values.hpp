#pragma once
// Typed reading of YAML nodes with diagnostics. Every reader reports what it expected and what
// it found at the node's position, and returns nullopt on a problem so that the caller can go
// on looking for more problems. This is the only place (with load.cpp) that knows about YAML.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "diagnostics.hpp"
#include "discreel/scene.hpp"
#include "discreel/vec2.hpp"

namespace discreel::scene::detail {

// The largest magnitude read_number accepts.
inline constexpr double max_scene_number = 1e15;

// A node and how to talk about it.
struct Value {
    YAML::Node node;
    Location where;      // the value itself, or its key when the value is empty
    std::string path;    // how messages name it: "discs[3].radius"

    bool is_null() const { return node.IsNull(); }

    // Copies share the node, as YAML::Node copies do. Assignment rebinds `node`: YAML::Node's
    // own assignment would write into the node it refers to.
    Value(const YAML::Node& node_, Location where_, std::string path_)
        : node(node_), where(where_), path(std::move(path_)) {}
    Value(const Value&) = default;
    Value& operator=(const Value& other) {
        node.reset(other.node);
        where = other.where;
        path = other.path;
        return *this;
    }
};

// yaml-cpp marks are 0-based and absent (-1) for empty nodes.
Location location_of(const YAML::Node& node, Location fallback);

// "nothing", "'abc'", "a list of 3 items", "a mapping": what the user wrote, for messages.
std::string describe(const YAML::Node& node);

// The keys of one mapping, checked against the keys it may have: unknown keys (with a
// suggestion), repeated keys and non-name keys are reported on construction.
class Fields {
public:
    // An empty value (`video:` with nothing under it) reads as an empty mapping.
    static std::optional<Fields> open(const Value& map, std::span<const std::string_view> known,
                                      Diagnostics& diagnostics);

    std::optional<Value> get(std::string_view key) const;
    bool has(std::string_view key) const { return find(key) != nullptr; }
    Location key_location(std::string_view key) const;  // only for keys that are present
    // Of two keys present, the one written later (where "not both" is reported).
    std::string_view later_of(std::string_view a, std::string_view b) const;
    Location where() const { return where_; }
    const std::string& path() const { return path_; }

    // Takes over `keys` from `inner` (a nested mapping whose keys may equally be written at
    // this level), so one lookup finds them in either place. A key written in both places is
    // reported at the inner one and the outer one is kept.
    void adopt(const Fields& inner, std::span<const std::string_view> keys,
               Diagnostics& diagnostics);

private:
    struct Entry {
        std::string key;
        Location key_where;
        Value value;
    };
    const Entry* find(std::string_view key) const;

    std::vector<Entry> entries_;  // first occurrence of each known key, in file order
    Location where_;
    std::string path_;
};

// The items of a list, each with its path ("walls[2]"). An empty value reads as an empty list.
std::optional<std::vector<Value>> read_list(const Value& value, Diagnostics& diagnostics);

// A list of exactly `size` items; `shape` describes it for messages: "[x, y]".
std::optional<std::vector<Value>> read_tuple(const Value& value, std::size_t size,
                                             std::string_view shape, Diagnostics& diagnostics);

std::optional<double> read_number(const Value& value, Diagnostics& diagnostics);   // finite
std::optional<long long> read_integer(const Value& value, Diagnostics& diagnostics);
std::optional<std::uint64_t> read_unsigned(const Value& value, Diagnostics& diagnostics);
std::optional<bool> read_bool(const Value& value, Diagnostics& diagnostics);
// One of `choices` (plain text, case-sensitive); the index of the one written.
std::optional<std::size_t> read_choice(const Value& value,
                                       std::span<const std::string_view> choices,
                                       Diagnostics& diagnostics);
std::optional<Color> read_color(const Value& value, Diagnostics& diagnostics);
std::optional<Vec2> read_vec2(const Value& value, std::string_view shape,
                              Diagnostics& diagnostics);

struct Corners {
    Vec2 a, b;
};
// [[x0, y0], [x1, y1]]
std::optional<Corners> read_corners(const Value& value, std::string_view shape,
                                    Diagnostics& diagnostics);

// Range checks: report "<path>: must be ..., got <v>" and return false when out of range.
bool check_between(const Value& value, double v, double lo, double hi, Diagnostics& diagnostics);
bool check_positive(const Value& value, double v, Diagnostics& diagnostics);
bool check_non_negative(const Value& value, double v, Diagnostics& diagnostics);

// Reads a number and checks it in one go; nullopt when either fails.
std::optional<double> read_positive(const Value& value, Diagnostics& diagnostics);
std::optional<double> read_non_negative(const Value& value, Diagnostics& diagnostics);
std::optional<double> read_between(const Value& value, double lo, double hi,
                                   Diagnostics& diagnostics);

}  // namespace discreel::scene::detail
