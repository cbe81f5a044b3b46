// The entry points: text or file in, a validated Scene and every problem found out.
#include <array>
#include <fstream>
#include <iterator>
#include <string_view>
#include <system_error>

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include "loader.hpp"

namespace discreel::scene {
namespace {

using detail::Diagnostics;
using detail::Fields;
using detail::Location;
using detail::Value;

constexpr std::array<std::string_view, 8> top_level_keys{
    "version", "video", "camera", "physics", "walls", "discs", "throws", "golden"};
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
    // Dependency order, not file order: discs take their defaults from physics, throws refer
    // to discs, golden frames are checked against the video's length.
    if (const auto v = fields->get("video")) detail::read_video(loader, *v);
    if (const auto v = fields->get("camera")) detail::read_camera(loader, *v);
    if (const auto v = fields->get("physics")) detail::read_physics(loader, *v);
    if (const auto v = fields->get("walls")) detail::read_walls(loader, *v);
    if (const auto v = fields->get("discs")) detail::read_discs(loader, *v);
    detail::check_discs(loader);
    if (const auto v = fields->get("throws")) detail::read_throws(loader, *v);
    detail::read_golden(loader, fields->get("golden"));
}

}  // namespace

LoadResult load_scene_text(std::string_view text, std::string_view display_name) {
    if (text.size() > max_file_bytes)
        return whole_file_problem(display_name, "the file is too large (" +
                                                    std::to_string(text.size()) +
                                                    " bytes); the limit is " +
                                                    std::to_string(max_file_bytes) + " bytes");
    LoadResult result;
    result.scene.name = std::filesystem::path(display_name).stem().string();
    Diagnostics d;
    std::vector<YAML::Node> documents;
    try {
        documents = YAML::LoadAll(std::string(text));
    } catch (const YAML::DeepRecursion& e) {
        d.error(mark_location(e.mark), "invalid YAML: nested too deeply");
    } catch (const YAML::ParserException& e) {
        d.error(mark_location(e.mark), "invalid YAML: " + e.msg);
    } catch (const YAML::Exception& e) {
        d.error(Location{}, "invalid YAML: " + e.msg);
    }
    if (d.empty()) {
        if (documents.empty() || documents[0].IsNull()) {
            d.error(Location{}, "the file is empty; a scene needs at least 'version: 1'");
        } else if (documents.size() > 1) {
            d.error(detail::location_of(documents[1], Location{}),
                    "the file holds more than one YAML document ('---'); a scene file holds one");
        } else {
            const Value root{documents[0], detail::location_of(documents[0], Location{}), ""};
            if (!root.node.IsMap()) {
                d.error(root.where, "a scene is a mapping of keys like 'version: 1' and 'discs:', "
                                    "got " + detail::describe(root.node));
            } else {
                detail::Loader loader{d, result.scene, {}, true, false, true};
                read_scene(root, loader);
            }
        }
    }
    result.diagnostics = std::move(d).finish(display_name);
    return result;
}

LoadResult load_scene_file(const std::filesystem::path& path) {
    const std::string display = path.string();
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        return whole_file_problem(display, "this is a directory, not a scene file");
    if (!std::filesystem::exists(path, ec)) return whole_file_problem(display, "no such file");
    const auto size = std::filesystem::file_size(path, ec);
    if (!ec && size > max_file_bytes)
        return whole_file_problem(display, "the file is too large (" + std::to_string(size) +
                                               " bytes); the limit is " +
                                               std::to_string(max_file_bytes) + " bytes");
    std::ifstream in(path, std::ios::binary);
    if (!in) return whole_file_problem(display, "cannot open the file for reading");
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad()) return whole_file_problem(display, "cannot read the file");
    return load_scene_text(text, display);
}

}  // namespace discreel::scene
