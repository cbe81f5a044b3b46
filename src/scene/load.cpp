// The entry points: text or file in, a validated Scene and every problem found out.
#include <algorithm>
#include <array>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include "discreel/read_file.hpp"
#include "loader.hpp"
#include "overrides.hpp"

namespace discreel::scene {
namespace {

using detail::Diagnostics;
using detail::Fields;
using detail::Location;
using detail::Value;

constexpr std::array<std::string_view, 14> top_level_keys{
    "version", "video", "audio", "camera", "style", "physics", "walls", "discs", "bodies",
    "throws", "joints", "golden", "warnings", "overlays"};
constexpr int supported_version = 1;
// Values under unknown top-level keys beyond which a file is refused before it is parsed into
// nodes: a misspelt section of an ordinary scene holds fewer, and is reported with the file's
// other problems instead.
constexpr std::size_t max_unknown_values = 10'000;

Location mark_location(const YAML::Mark& mark) {
    if (mark.is_null() || mark.line < 0 || mark.column < 0) return {};
    return {mark.line + 1, mark.column + 1};
}

LoadResult whole_file_problem(std::string_view file, std::string message) {
    LoadResult result;
    result.diagnostics.push_back({std::string(file), 0, 0, std::move(message)});
    return result;
}

std::string too_large(std::uintmax_t bytes, const Limits& limits) {
    return "the file is too large (" + std::to_string(bytes) + " bytes); the limit is " +
           std::to_string(limits.file_bytes) + " bytes (raise it with --max-scene-bytes)";
}

// A file written for a later format: its other keys may mean something this build does not
// know, so only the version is reported. Returns false when it is such a file.
bool version_supported(const Value& root, Diagnostics& d) {
    const YAML::Node version = root.node["version"];
    if (!version || !version.IsScalar()) return true;  // reported with the other keys
    Value value{version, detail::location_of(version, root.where), "version"};
    Diagnostics quiet;
    const auto number = detail::read_integer(value, quiet);
    if (!number || *number == supported_version) return true;
    d.error(value.where, "version: this file is format version " + std::to_string(*number) +
                             ", but this build of discreel reads only version " +
                             std::to_string(supported_version));
    return false;
}

// yaml-cpp 0.7's LoadAll never returns when a document's root is a token the parser cannot
// place, such as a ',' outside [...] or {...} (jbeder/yaml-cpp#1040): it reports an empty
// document without consuming the token, over and over, until memory runs out. So an event-only
// pass looks at the documents first: where they start, whether the first is empty, and a
// document that starts exactly where the previous one did, which is that stuck token. Nodes
// are then built for the first document only; a scene file holds one.
//
// The same pass counts the values that aliases repeat. yaml-cpp shares an anchored node rather
// than copying it, but the loader reads every use: a few kilobytes of nested aliases (a
// "billion laughs") or ten thousand throws aliasing one long path would otherwise cost hours
// and gigabytes, where the file-size limit bounds everything written out.
//
// The pass also refuses, before a single node is built, what cannot be a scene: more values
// than limits.values, more entries in discs, walls or throws than their limits, and unknown
// top-level keys that hold more than max_unknown_values. It stops reading at the first such
// finding, so a huge file of junk costs one partial read of events.
class DocumentScan final : public YAML::EventHandler {
public:
    DocumentScan(std::string_view text, const Limits& limits) : limits_(limits) {
        std::istringstream stream{std::string(text)};
        YAML::Parser parser(stream);
        // A second document is an error, more add nothing; but a stuck token right after the
        // first document shows only as a third that starts where the second did.
        try {
            while (count_ <= 2 && !stuck_ && parser.HandleNextDocument(*this)) {}
        } catch (const Refused&) {
            // refusal_ says why
        }
    }

    // Why the file cannot be a scene, and where, when the pass found out.
    const std::optional<std::pair<Location, std::string>>& refusal() const { return refusal_; }

    bool first_is_empty() const { return count_ == 0 || first_is_null_; }
    // Where the second document's root is, when there is one.
    std::optional<Location> second() const {
        return count_ > 1 ? std::optional{second_root_} : std::nullopt;
    }
    // Where the stuck token is, when there is one.
    std::optional<YAML::Mark> stuck() const { return stuck_; }
    // The alias that took the values repeated by aliases past max_alias_values, if any.
    std::optional<YAML::Mark> too_many_aliased() const { return too_many_aliased_; }

    void OnDocumentStart(const YAML::Mark& mark) override {
        if (last_start_ && last_start_->pos == mark.pos) {
            stuck_ = mark;
            return;
        }
        last_start_ = mark;
        ++count_;
        at_root_ = true;
        anchored_sizes_.clear();  // anchors are numbered per document
    }
    void OnDocumentEnd() override {}
    void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override {
        begin_node(mark, nullptr);
        root(mark, true);
        leaf(anchor, 1);
    }
    void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
        begin_node(mark, nullptr);
        root(mark, false);
        const std::size_t size = anchor < anchored_sizes_.size() ? anchored_sizes_[anchor] : 1;
        aliased_ = capped_sum(aliased_, size);
        if (aliased_ > max_alias_values && !too_many_aliased_) too_many_aliased_ = mark;
        leaf(0, size);
    }
    void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  const std::string& value) override {
        begin_node(mark, &value);
        root(mark, false);
        leaf(anchor, 1);
    }
    void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                         YAML::EmitterStyle::value) override {
        begin_node(mark, nullptr);
        root(mark, false);
        open_.push_back({anchor, 1, false, 0});
    }
    void OnSequenceEnd() override { close(); }
    void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                    YAML::EmitterStyle::value) override {
        begin_node(mark, nullptr);
        root(mark, false);
        open_.push_back({anchor, 1, true, 0});
    }
    void OnMapEnd() override { close(); }

private:
    // A collection being read: its anchor (0: none) and how many values it holds with every
    // alias in it expanded, itself included.
    struct Open {
        YAML::anchor_t anchor;
        std::size_t size;
        bool is_map;
        std::size_t children;   // nodes directly inside so far (a map's keys and values)
    };

    static std::size_t capped_sum(std::size_t a, std::size_t b) {
        return std::min(a + b, max_alias_values + 1);  // both are capped: no overflow
    }
    void leaf(YAML::anchor_t anchor, std::size_t size) {
        if (anchor != 0) {
            if (anchored_sizes_.size() <= anchor) anchored_sizes_.resize(anchor + 1, 1);
            anchored_sizes_[anchor] = size;
        }
        if (!open_.empty()) open_.back().size = capped_sum(open_.back().size, size);
    }
    void close() {
        const Open done = open_.back();
        open_.pop_back();
        leaf(done.anchor, done.size);
    }
    void root(const YAML::Mark& mark, bool is_null) {
        if (!at_root_) return;
        at_root_ = false;
        if (count_ == 1) first_is_null_ = is_null;
        if (count_ == 2) second_root_ = mark_location(mark);
    }

    struct Refused {};
    void refuse(const YAML::Mark& mark, std::string message) {
        refusal_.emplace(mark_location(mark), std::move(message));
        throw Refused{};
    }

    // Every node of the first document passes here as it starts, before root() and before it
    // joins its parent; `scalar` is its text when it is a scalar.
    void begin_node(const YAML::Mark& mark, const std::string* scalar) {
        if (count_ != 1) return;
        if (++values_ > limits_.values) {
            refuse(mark, "the file holds more than " + std::to_string(limits_.values) +
                             " YAML values (scalars, lists and mappings), the limit; raise it "
                             "with --max-scene-values");
        }
        if (open_.empty()) return;
        Open& parent = open_.back();
        const std::size_t index = parent.children++;
        if (open_.size() == 1 && parent.is_map) {
            if (index % 2 == 0) {   // a top-level key
                section_.clear();
                key_mark_ = mark;
                if (scalar) section_ = *scalar;
                known_section_ = std::find(top_level_keys.begin(), top_level_keys.end(),
                                           section_) != top_level_keys.end();
            }
            return;
        }
        if (!known_section_ && ++unknown_values_ > max_unknown_values) {
            refuse(key_mark_, "unknown top-level key '" + section_ +
                                  "', holding more values than any scene needs; expected one "
                                  "of: version, video, camera, style, physics, walls, discs, "
                                  "bodies, throws, joints, golden");
        }
        if (open_.size() == 2 && !parent.is_map) {   // an entry of a top-level list
            const std::size_t entries = index + 1;
            // Each entry of `discs` or `bodies` makes at least one body; both count together.
            if ((section_ == "discs" || section_ == "bodies") && ++body_entries_ > limits_.bodies) {
                refuse(mark, section_ + ": more than " + std::to_string(limits_.bodies) +
                                 " entries in 'discs' and 'bodies', and each makes at least one "
                                 "body; the limit is " +
                                 std::to_string(limits_.bodies) + " (raise it with --max-bodies)");
            }
            if (section_ == "walls" && entries > max_walls) {
                refuse(mark, "walls: too many walls (more than " + std::to_string(max_walls) +
                                 "); the limit is " + std::to_string(max_walls));
            }
            if (section_ == "throws" && entries > max_throws) {
                refuse(mark, "throws: too many throws (more than " + std::to_string(max_throws) +
                                 "); the limit is " + std::to_string(max_throws));
            }
            if (section_ == "joints" && entries > max_joints) {
                refuse(mark, "joints: too many joints (more than " + std::to_string(max_joints) +
                                 "); the limit is " + std::to_string(max_joints));
            }
        }
    }

    std::size_t count_ = 0;
    bool at_root_ = false;
    bool first_is_null_ = false;
    Location second_root_;
    std::optional<YAML::Mark> last_start_;
    std::optional<YAML::Mark> stuck_;
    std::vector<Open> open_;
    std::vector<std::size_t> anchored_sizes_;  // by anchor number
    std::size_t aliased_ = 0;                  // values repeated by aliases, capped
    std::optional<YAML::Mark> too_many_aliased_;
    const Limits& limits_;
    std::size_t values_ = 0;          // nodes of the first document so far
    std::size_t body_entries_ = 0;    // entries of `discs` and `bodies` so far
    std::string section_;             // the top-level key being read
    YAML::Mark key_mark_;
    bool known_section_ = true;
    std::size_t unknown_values_ = 0;  // nodes under unknown top-level keys
    std::optional<std::pair<Location, std::string>> refusal_;
};

std::string stuck_token_message(std::string_view text, const YAML::Mark& mark) {
    const auto at = static_cast<std::size_t>(mark.pos);
    if (at < text.size() && text[at] == ',')
        return "invalid YAML: a ',' outside [...] or {...}; commas separate items only inside "
               "brackets or braces";
    return "invalid YAML: unexpected text where a value should start";
}

void read_scene(const Value& root, detail::Loader& loader) {
    auto& d = loader.diagnostics;
    if (!version_supported(root, d)) return;
    const auto fields = Fields::open(root, top_level_keys, d);
    if (!fields) return;
    if (const auto version = fields->get("version")) {
        const auto number = detail::read_integer(*version, d);
        if (number) loader.scene.version = static_cast<int>(*number);
    } else {
        d.error(root.where, "missing required key 'version'; start the file with 'version: 1'");
    }
    // Dependency order, not file order: discs take their defaults from physics, throws,
    // joints and camera.follow refer to discs (joined bodies may overlap at t = 0), golden frames are checked against the video's length.
    if (const auto v = fields->get("video")) detail::read_video(loader, *v);
    if (const auto v = fields->get("audio")) detail::read_audio(loader, *v);
    if (const auto v = fields->get("camera")) detail::read_camera(loader, *v);
    const auto physics = fields->get("physics");
    if (physics) detail::read_physics(loader, *physics);
    if (d.empty()) {
        // The work the clip asks for, pointed at the setting most likely to be the cause.
        if (auto problem = check_work(loader.scene, loader.limits)) {
            const auto video = fields->get("video");
            d.error(physics ? physics->where : video ? video->where : root.where, *problem);
        }
    }
    if (const auto v = fields->get("walls")) detail::read_walls(loader, *v);
    if (const auto v = fields->get("discs")) detail::read_discs(loader, *v);
    if (const auto v = fields->get("bodies"); v && !loader.disc_limit_reached) {
        detail::read_bodies(loader, *v);
    }
    if (const auto v = fields->get("joints"); v && !loader.disc_limit_reached) {
        detail::read_joints(loader, *v);
    }
    detail::check_discs(loader);
    detail::resolve_camera_follow(loader);
    if (const auto v = fields->get("style")) detail::read_style(loader, *v);
    if (loader.discs_complete) {
        detail::read_labels(loader);
        if (const auto v = fields->get("overlays")) detail::read_overlays(loader, *v);
    }
    if (const auto v = fields->get("throws")) detail::read_throws(loader, *v);
    detail::check_ranges(loader);
    if (d.empty()) detail::check_envelope(loader);
    detail::read_golden(loader, fields->get("golden"));
    // `warnings: false`: the author has read them; errors are never silenced.
    if (const auto v = fields->get("warnings")) {
        if (const auto on = detail::read_bool(*v, d); on && !*on) loader.scene.warnings = false;
    }
}

// yaml-cpp breaks lines at "\n" and "\r\n" only; a file with old Mac line ends ("\r" alone)
// would be one long line, and every position in it wrong. Same length: columns stay true.
std::string with_line_feeds(std::string_view text) {
    std::string out(text);
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (out[i] == '\r' && (i + 1 == out.size() || out[i + 1] != '\n')) out[i] = '\n';
    }
    return out;
}

// An unquoted colour inside {...} or [...]: `{color: #ff0000}`. YAML reads everything from
// the '#' on as a comment, the closing bracket included, so the parser fails lines later. Where
// each one starts (the '#'), found by a scan that knows quotes, comments and bracket depth.
bool is_hex(char c) {
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}

std::vector<std::size_t> unquoted_flow_colours(std::string_view text) {
    std::vector<std::size_t> found;
    int depth = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '"' || c == '\'') {
            // Quoted scalars: '' escapes a single quote, backslash escapes in double quotes.
            for (++i; i < text.size(); ++i) {
                if (c == '"' && text[i] == '\\') {
                    ++i;
                } else if (text[i] == c) {
                    if (c == '\'' && i + 1 < text.size() && text[i + 1] == '\'') {
                        ++i;
                    } else {
                        break;
                    }
                }
            }
        } else if (c == '{' || c == '[') {
            ++depth;
        } else if ((c == '}' || c == ']') && depth > 0) {
            --depth;
        } else if (c == '#' && (i == 0 || text[i - 1] == ' ' || text[i - 1] == '\t' ||
                                text[i - 1] == '\n')) {
            std::size_t end = i + 1;
            while (end < text.size() && is_hex(text[end])) ++end;
            const std::size_t digits = end - i - 1;
            // A colour is followed by what ends a flow item; a comment's text (`#add`,
            // `#cafe`) at the end of a line inside a multi-line [...] is not taken for one.
            const bool terminated = end < text.size() &&
                                    std::string_view(",}]").find(text[end]) !=
                                        std::string_view::npos;
            if (depth > 0 && (digits == 3 || digits == 4 || digits == 6 || digits == 8) &&
                terminated) {
                found.push_back(i);
                i = end - 1;
            } else {
                while (i < text.size() && text[i] != '\n') ++i;   // a comment
            }
        }
    }
    return found;
}

Location location_at(std::string_view text, std::size_t offset) {
    Location where;
    for (std::size_t i = 0; i < offset; ++i) {
        if (text[i] == '\n') {
            ++where.line;
            where.column = 1;
        } else {
            ++where.column;
        }
    }
    return where;
}

}  // namespace

LoadResult load_scene_text(std::string_view original_text, std::string_view display_name,
                           const Limits& limits, std::optional<double> clip_duration,
                           std::span<const Override> overrides) {
    if (original_text.size() > limits.file_bytes)
        return whole_file_problem(display_name, too_large(original_text.size(), limits));
    std::string normalised = with_line_feeds(original_text);
    // Unquoted colours in flow style break the YAML far from where they are. Each is reported
    // where it is, and the file is read on with a stand-in in its place (same length, so every
    // other position stays true) to find its other problems too.
    std::vector<Location> colours;
    for (const std::size_t at : unquoted_flow_colours(normalised)) {
        colours.push_back(location_at(normalised, at));
        normalised[at] = 'x';
    }
    const std::string_view text = normalised;
    LoadResult result;
    result.scene.name = std::filesystem::path(display_name).stem().string();
    Diagnostics d;
    YAML::Node document;
    std::optional<Location> second_document;
    try {
        const DocumentScan scan(text, limits);
        if (const auto& refusal = scan.refusal()) {
            d.error(refusal->first, refusal->second);
        } else if (const auto stuck = scan.stuck()) {
            d.error(mark_location(*stuck), stuck_token_message(text, *stuck));
        } else if (const auto alias = scan.too_many_aliased()) {
            d.error(mark_location(*alias),
                    "aliases (*name) repeat more than " + std::to_string(max_alias_values) +
                        " values in this file, the limit; write the values out instead");
        } else if (!scan.first_is_empty()) {
            second_document = scan.second();
            if (!second_document) document = YAML::Load(std::string(text));
        }
    } catch (const YAML::DeepRecursion& e) {
        d.error(mark_location(e.mark), "invalid YAML: nested too deeply");
    } catch (const YAML::ParserException& e) {
        d.error(mark_location(e.mark), "invalid YAML: " + e.msg);
    } catch (const YAML::Exception& e) {
        d.error(Location{}, "invalid YAML: " + e.msg);
    }
    if (d.empty()) {
        if (second_document) {
            d.error(*second_document,
                    "the file holds more than one YAML document ('---'); a scene file holds one");
        } else if (!document || document.IsNull()) {
            d.error(Location{}, "the file is empty; a scene needs at least 'version: 1'");
        } else {
            const Value root{document, detail::location_of(document, Location{}), ""};
            if (!root.node.IsMap()) {
                d.error(root.where, "a scene is a mapping of keys like 'version: 1' and 'discs:', "
                                    "got " + detail::describe(root.node));
            } else {
                const int lines = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
                detail::apply_overrides(document, overrides, lines + 2, d);
                detail::Loader loader{d, result.scene, {}, true, false, true, {}, {}, limits,
                                      clip_duration, {}, {}, {}};
                read_scene(root, loader);
            }
        }
    }
    for (const Location& where : colours) {
        d.error(where, "a colour in {...} or [...] must be quoted: YAML reads an unquoted '#' "
                       "as the start of a comment, which hides the closing bracket; write "
                       "color: \"#rrggbb\"");
    }
    if (d.empty()) result.warnings = d.take_warnings(display_name);
    if (!result.scene.warnings) result.warnings.clear();
    result.diagnostics = std::move(d).finish(display_name);
    // What the stand-ins caused (a colour that is no colour) is said already.
    std::erase_if(result.diagnostics, [&](const Diagnostic& x) {
        return std::find(colours.begin(), colours.end(), Location{x.line, x.column}) !=
                   colours.end() &&
               x.message.find("must be quoted") == std::string::npos;
    });
    return result;
}

LoadResult load_scene_file(const std::filesystem::path& path, const Limits& limits,
                           std::optional<double> clip_duration,
                           std::span<const Override> overrides) {
    const std::string display = path.string();
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        return whole_file_problem(display, "this is a directory, not a scene file");
    if (!std::filesystem::exists(path, ec)) return whole_file_problem(display, "no such file");
    const auto size = std::filesystem::file_size(path, ec);
    if (!ec && size > limits.file_bytes) return whole_file_problem(display, too_large(size, limits));
    // Whatever the file is (a pipe, /dev/zero, a file still growing), no more than the limit
    // and one byte is read.
    auto read = read_file_bounded(display, limits.file_bytes);
    if (!read) return whole_file_problem(display, "cannot read the file: " + read.error().message);
    if (read->too_large) {
        return whole_file_problem(display, "the input holds more than " +
                                               std::to_string(limits.file_bytes) +
                                               " bytes, the limit (raise it with "
                                               "--max-scene-bytes)");
    }
    return load_scene_text(read->bytes, display, limits, clip_duration, overrides);
}

}  // namespace discreel::scene
