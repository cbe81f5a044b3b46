#include "request.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <limits>
#include <optional>

#include "digest.hpp"
#include "discreel/render.hpp"
#include "discreel/parse_number.hpp"

namespace discreel::serve {
namespace {

using nlohmann::json;

constexpr std::array<const char*, 6> formats{"mp4", "webm", "mkv", "gif", "png", "wav"};

// A body is one object whose only nested value is `set`, an object of scene values (lists
// of numbers at most: `"video.size": [128, 128]`); anything nested deeper is refused while
// parsing, before it is built, so no body can make the parser or the value's destructor
// recurse deeply.
constexpr int max_depth = 4;

// More values in `set` than any variant of a scene needs: the rest belongs in the scene.
constexpr std::size_t max_set_values = 256;

// How a problem with one of `set`'s values is named (Override::label).
std::string set_label(const std::string& key) { return "set '" + key + "'"; }

struct TooDeep {};

std::optional<std::string> type_problem(const std::string& key, const json& value) {
    const auto must_be = [&](const char* what) {
        return "field '" + key + "' must be " + what;
    };
    if (key == "scene" || key == "output" || key == "size" || key == "preset" ||
        key == "frames" || key == "callback") {
        if (!value.is_string()) return must_be("a string");
    } else if (key == "outputs") {
        if (!value.is_array() || value.empty()) return must_be("a list of output names");
        for (const auto& item : value) {
            if (!item.is_string()) return must_be("a list of output names");
        }
    } else if (key == "set") {
        if (!value.is_object()) return must_be("an object of scene paths and values, e.g. "
                                               "{\"physics.seed\": 3}");
        if (value.size() > max_set_values) {
            return "field 'set' holds " + std::to_string(value.size()) + " values; at most " +
                   std::to_string(max_set_values);
        }
        for (const auto& [path, v] : value.items()) {
            if (v.is_object()) return "field 'set': the value of '" + path + "' is an object; "
                                      "set its keys one by one ('" + path + ".KEY')";
        }
    } else if (key == "frame" || key == "fps" || key == "crf") {
        if (!value.is_number_integer()) return must_be("an integer");
    } else if (key == "at" || key == "duration") {
        if (!value.is_number()) return must_be("a number");
    } else if (key == "audio") {
        if (!value.is_boolean()) return must_be("true or false");
    }
    return std::nullopt;
}

bool known_field(const std::string& key) {
    for (const char* name : {"scene", "output", "outputs", "frame", "frames", "at", "size",
                             "fps", "duration", "crf", "preset", "audio", "set", "callback"}) {
        if (key == name) return true;
    }
    return false;
}

// An integer field within int's range.
std::optional<int> small_int(const json& value) {
    if (value.is_number_unsigned()) {
        const auto v = value.get<std::uint64_t>();
        if (v > static_cast<std::uint64_t>(std::numeric_limits<int>::max())) return std::nullopt;
        return static_cast<int>(v);
    }
    const auto v = value.get<std::int64_t>();
    if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max()) {
        return std::nullopt;
    }
    return static_cast<int>(v);
}

// The job layer's messages name the command line's options; a service client sends fields,
// and cannot pass the options only the server's operator sets. The same advice in its terms.
std::string in_service_terms(std::string message) {
    static const std::array<std::pair<const char*, const char*>, 14> words{{
        {"; PNG, GIF and --pix-fmt yuv444p take any size", "; PNG and GIF take any size"},
        {"(raise the limit with --max-duration)", "(the server's --max-duration)"},
        {"(raise it with --max-substeps)", "(the server's --max-substeps)"},
        {"(raise it with --max-scene-bytes)", "(the server's --max-scene-bytes)"},
        {"--frames", "'frames'"},
        {"--frame", "'frame'"},
        {"--at", "'at'"},
        {"--size", "'size'"},
        {"--fps", "'fps'"},
        {"--duration", "'duration'"},
        {"--crf", "'crf'"},
        {"--preset", "'preset'"},
        {"--audio", "'audio'"},
        {"a numbered .png name writes every frame", "'output' png is one still"},
    }};
    for (const auto& [from, to] : words) {
        const std::string_view f = from;
        for (auto at = message.find(f); at != std::string::npos; at = message.find(f, at)) {
            // "--frame" must not take the start of "--frames".
            const std::size_t end = at + f.size();
            if (f.rfind("--", 0) == 0 && end < message.size() &&
                (std::isalnum(static_cast<unsigned char>(message[end])) != 0 ||
                 message[end] == '-')) {
                at = end;
                continue;
            }
            message.replace(at, f.size(), to);
            at += std::string_view(to).size();
        }
    }
    return message;
}

json one_error(const json& line, const json& column, const std::string& message) {
    return json{{"line", line}, {"column", column}, {"message", message}};
}

// Diagnostics as [{"line", "column", "message"}, ...].
json placed(const std::vector<scene::Diagnostic>& diagnostics) {
    json list = json::array();
    for (const scene::Diagnostic& d : diagnostics) {
        if (d.line <= 0 && d.file != "scene") {   // one of `set`'s values: no place in the scene
            list.push_back(one_error(nullptr, nullptr, d.file + ": " + in_service_terms(d.message)));
        } else {
            list.push_back(one_error(d.line, d.column, in_service_terms(d.message)));
        }
    }
    return list;
}

}  // namespace

Refusal refusal(int status, const std::string& message) {
    return Refusal{status, json{{"error", {{"message", message}}}}};
}

std::string JobRequest::stored() const {
    json all = options;
    all["scene"] = scene;
    return all.dump();
}

const char* extension_of(const std::string& side_output) {
    if (side_output == "shapes") return "json";
    if (side_output == "masks") return "tar";
    return "csv";
}

const char* content_type_of(const std::string& format) {
    if (format == "csv") return "text/csv; charset=utf-8";
    if (format == "json") return "application/json";
    if (format == "tar") return "application/x-tar";
    if (format == "mp4") return "video/mp4";
    if (format == "webm") return "video/webm";
    if (format == "mkv") return "video/x-matroska";
    if (format == "gif") return "image/gif";
    if (format == "wav") return "audio/wav";
    return "image/png";
}

std::variant<JobRequest, Refusal> parse_job_request(std::string_view body,
                                                    const scene::Limits& limits,
                                                    const std::string& version) {
    json parsed;
    try {
        parsed = json::parse(body, [](int depth, json::parse_event_t, json&) {
            if (depth > max_depth) throw TooDeep{};
            return true;
        });
    } catch (const json::parse_error& e) {
        return refusal(400, std::string("the body is not JSON: ") + e.what());
    } catch (const json::out_of_range& e) {   // a number beyond a double, such as 1e400
        return refusal(400, std::string("a number in the body is out of range: ") + e.what());
    } catch (const TooDeep&) {
        return refusal(400, "the body nests too deeply: it is one JSON object of strings, numbers and `set`");
    }
    if (!parsed.is_object()) return refusal(400, "the body must be a JSON object");
    for (const auto& [key, value] : parsed.items()) {
        if (!known_field(key)) {
            return refusal(400, "unknown field '" + key + "'; the fields are scene, output, "
                                "outputs, frame, frames, at, size, fps, duration, crf, preset, "
                                "audio, set and callback");
        }
        if (auto problem = type_problem(key, value)) return refusal(400, *problem);
    }
    if (!parsed.contains("scene")) {
        return refusal(400, "field 'scene' (the scene's YAML) is required");
    }
    JobRequest request;
    request.scene = parsed["scene"].get<std::string>();
    if (request.scene.size() > limits.file_bytes) {
        return refusal(413, "the scene is " + std::to_string(request.scene.size()) +
                                " bytes, over the limit of " + std::to_string(limits.file_bytes));
    }
    request.format = parsed.value("output", "mp4");
    bool known_format = false;
    for (const char* format : formats) known_format = known_format || request.format == format;
    if (!known_format) {
        return refusal(400, "field 'output' must be one of mp4, webm, mkv, gif, png, wav");
    }
    if (parsed.contains("outputs")) {
        // The media format among them is the main output (`output` may say the same); the
        // rest are side outputs, each once.
        std::optional<std::string> media;
        for (const auto& item : parsed["outputs"]) {
            const std::string name = item.get<std::string>();
            const bool is_media = std::find(formats.begin(), formats.end(), name) != formats.end();
            const bool is_side =
                std::find(side_outputs.begin(), side_outputs.end(), name) != side_outputs.end();
            if (!is_media && !is_side) {
                return refusal(400, "field 'outputs': unknown output '" + name +
                                        "'; the outputs are mp4, webm, mkv, gif, png, wav (one "
                                        "of them) and trace, events, joints, shapes, camera, "
                                        "masks, boxes");
            }
            if (is_media) {
                if (media || (parsed.contains("output") && parsed["output"] != name)) {
                    return refusal(400, "field 'outputs' names one video or image format, the "
                                        "same as 'output' if both are given");
                }
                media = name;
                continue;
            }
            if (std::find(request.extras.begin(), request.extras.end(), name) !=
                request.extras.end()) {
                return refusal(400, "field 'outputs' names '" + name + "' twice");
            }
            request.extras.push_back(name);
        }
        if (media) request.format = *media;
    }
    if (request.format == "wav" && !request.extras.empty()) {
        return refusal(400, "field 'outputs': a wav soundtrack has no frames: trace, events, "
                            "joints and the ground truth come with a video or images");
    }
    parsed.erase("scene");
    parsed["output"] = request.format;
    job::RenderRequest& render = request.render;
    render.output = "render." + request.format;
    for (const char* key : {"frame", "fps", "crf"}) {
        if (!parsed.contains(key)) continue;
        const auto value = small_int(parsed[key]);
        if (!value) return refusal(400, std::string("field '") + key + "' is out of range");
        if (std::string_view(key) == "frame") render.frame = *value;
        if (std::string_view(key) == "fps") render.video.fps = *value;
        if (std::string_view(key) == "crf") render.crf = *value;
    }
    if (parsed.contains("at")) render.at = parsed["at"].get<double>();
    if (parsed.contains("duration")) render.video.duration = parsed["duration"].get<double>();
    if (parsed.contains("preset")) render.preset = parsed["preset"].get<std::string>();
    if (parsed.contains("frames")) render.frames = parsed["frames"].get<std::string>();
    if (parsed.contains("set")) {
        // JSON is YAML: each value is read by the scene's loader as written.
        for (const auto& [path, value] : parsed["set"].items()) {
            request.overrides.push_back({path, value.dump(), set_label(path)});
        }
    }
    if (parsed.contains("audio")) render.audio = parsed["audio"].get<bool>();
    if (parsed.contains("callback")) {
        auto url = parse_callback_url(parsed["callback"].get<std::string>());
        if (!url) return refusal(400, "field 'callback': " + url.error().message);
        request.callback = *url;
    }
    if (parsed.contains("size")) {
        const auto size = parse_size(parsed["size"].get<std::string>());
        if (!size) return refusal(400, "field 'size' must be WIDTHxHEIGHT, e.g. \"320x180\"");
        render.video.width = size->first;
        render.video.height = size->second;
    }
    request.options = std::move(parsed);
    // The same request is the same job: discreel's version, the options (object keys sorted by
    // nlohmann::json, numbers printed exactly) and the scene's bytes.
    request.id = sha256_hex("discreel " + version + "\n" + request.options.dump() + "\n" +
                            request.scene)
                     .substr(0, 32);
    return request;
}

std::variant<PlannedJob, Refusal> plan_job(const JobRequest& request,
                                           const scene::Limits& limits) {
    scene::LoadResult loaded =
        scene::load_scene_text(request.scene, "scene", limits, request.render.video.duration,
                               request.overrides);
    if (!loaded.ok()) return Refusal{422, json{{"errors", placed(loaded.diagnostics)}}};
    json warnings = placed(loaded.warnings);
    const bool masked = std::any_of(request.extras.begin(), request.extras.end(),
                                    [](const std::string& e) { return e == "masks" || e == "boxes"; });
    if (masked && loaded.scene.bodies.size() >= render::wall_mask_id) {
        return Refusal{422, json{{"errors", json::array({one_error(
                                                nullptr, nullptr,
                                                "'outputs' masks and boxes number bodies in 16 "
                                                "bits: at most " +
                                                    std::to_string(render::wall_mask_id - 1) +
                                                    " bodies, and the scene has " +
                                                    std::to_string(loaded.scene.bodies.size()))})}}};
    }
    auto plan = job::plan_render(std::move(loaded.scene), request.render, limits);
    if (!plan) {
        return Refusal{422, json{{"errors", json::array({one_error(
                                                nullptr, nullptr,
                                                in_service_terms(plan.error().message))})}}};
    }
    return PlannedJob{std::move(*plan), std::move(warnings)};
}

}  // namespace discreel::serve
