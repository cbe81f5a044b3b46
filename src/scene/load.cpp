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

#include "loader.hpp"

namespace discreel::scene {
namespace {

using detail::Diagnostics;
using detail::Fields;
using detail::Location;
using detail::Value;

constexpr std::array<std::string_view, 9> top_level_keys{
    "version", "video", "camera", "style", "physics", "walls", "discs", "throws", "golden"};
constexpr int supported_version = 1;

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
class DocumentScan final : public YAML::EventHandler {
public:
    explicit DocumentScan(std::string_view text) {
        std::istringstream stream{std::string(text)};
        YAML::Parser parser(stream);
        // A second document is an error, more add nothing; but a stuck token right after the
        // first document shows only as a third that starts where the second did.
        while (count_ <= 2 && !stuck_ && parser.HandleNextDocument(*this)) {}
    }

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
        root(mark, true);
        leaf(anchor, 1);
    }
    void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
        root(mark, false);
        const std::size_t size = anchor < anchored_sizes_.size() ? anchored_sizes_[anchor] : 1;
        aliased_ = capped_sum(aliased_, size);
        if (aliased_ > max_alias_values && !too_many_aliased_) too_many_aliased_ = mark;
        leaf(0, size);
    }
    void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  const std::string&) override {
        root(mark, false);
        leaf(anchor, 1);
    }
    void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                         YAML::EmitterStyle::value) override {
        root(mark, false);
        open_.push_back({anchor, 1});
    }
    void OnSequenceEnd() override { close(); }
    void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                    YAML::EmitterStyle::value) override {
        root(mark, false);
        open_.push_back({anchor, 1});
    }
    void OnMapEnd() override { close(); }

private:
    // A collection being read: its anchor (0: none) and how many values it holds with every
    // alias in it expanded, itself included.
    struct Open {
        YAML::anchor_t anchor;
        std::size_t size;
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
    // Dependency order, not file order: discs take their defaults from physics, throws and
    // camera.follow refer to discs, golden frames are checked against the video's length.
    if (const auto v = fields->get("video")) detail::read_video(loader, *v);
    if (const auto v = fields->get("camera")) detail::read_camera(loader, *v);
    if (const auto v = fields->get("physics")) detail::read_physics(loader, *v);
    if (const auto v = fields->get("walls")) detail::read_walls(loader, *v);
    if (const auto v = fields->get("discs")) detail::read_discs(loader, *v);
    detail::check_discs(loader);
    detail::resolve_camera_follow(loader);
    if (const auto v = fields->get("style")) detail::read_style(loader, *v);
    if (const auto v = fields->get("throws")) detail::read_throws(loader, *v);
    if (d.empty()) detail::check_envelope(loader);
    detail::read_golden(loader, fields->get("golden"));
}

}  // namespace

LoadResult load_scene_text(std::string_view text, std::string_view display_name,
                           const Limits& limits) {
    if (text.size() > limits.file_bytes)
        return whole_file_problem(display_name, too_large(text.size(), limits));
    LoadResult result;
    result.scene.name = std::filesystem::path(display_name).stem().string();
    Diagnostics d;
    YAML::Node document;
    std::optional<Location> second_document;
    try {
        const DocumentScan scan(text);
        if (const auto stuck = scan.stuck()) {
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
                detail::Loader loader{d, result.scene, {}, true, false, true, {}, {}, limits};
                read_scene(root, loader);
            }
        }
    }
    result.diagnostics = std::move(d).finish(display_name);
    return result;
}

LoadResult load_scene_file(const std::filesystem::path& path, const Limits& limits) {
    const std::string display = path.string();
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        return whole_file_problem(display, "this is a directory, not a scene file");
    if (!std::filesystem::exists(path, ec)) return whole_file_problem(display, "no such file");
    const auto size = std::filesystem::file_size(path, ec);
    if (!ec && size > limits.file_bytes) return whole_file_problem(display, too_large(size, limits));
    std::ifstream in(path, std::ios::binary);
    if (!in) return whole_file_problem(display, "cannot open the file for reading");
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad()) return whole_file_problem(display, "cannot read the file");
    return load_scene_text(text, display, limits);
}

}  // namespace discreel::scene
