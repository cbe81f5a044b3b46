// The table of output formats: what a path names, which settings it takes, which sink writes it.
#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <string_view>

#include "discreel/commit.hpp"
#include "discreel/encode.hpp"
#include "frame_pattern.hpp"
#include "discreel/output_file.hpp"
#include "png_sequence_sink.hpp"
#include "png_still_sink.hpp"
#include "video_format.hpp"
#include "video_sink.hpp"

namespace discreel::encode {
namespace {

using FormatBuilder = Expected<VideoFormat> (*)(const SinkDef&);

struct OutputKind {
    std::string_view name;        // extension with the dot, or "-" for standard output
    std::string_view summary;     // for the list of supported formats
    std::string_view format;      // OutputDescription::format
    FormatBuilder video;          // null: PNG (a still, or a sequence for a numbered name)
};

// A new container or codec is a VideoFormat builder plus one row here.
constexpr std::array<OutputKind, 6> output_kinds = {{
    {".mp4", ".mp4 (H.264)", "mp4", mp4_format},
    {".mkv", ".mkv (H.264, VP9, or FFV1 lossless)", "mkv", mkv_format},
    {".webm", ".webm (VP9)", "webm", webm_format},
    {".gif", ".gif", "gif", gif_format},
    {".png", ".png (one frame, or every frame for a numbered name such as frame_%04d.png)",
     "png", nullptr},
    {"-", "- (Matroska or fragmented MP4 on standard output)",
     "mkv", stream_format},
}};

std::string supported_formats() {
    std::string list;
    for (const auto& kind : output_kinds) {
        list += (list.empty() ? "" : ", ") + std::string(kind.summary);
    }
    return list + ", .wav (the soundtrack alone)";
}

// The extension of `path`, lower-case, with its dot; "-" for standard output.
std::string extension_of(const std::string& path) {
    std::string extension = path == "-" ? path : std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension;
}

// A .wav is the soundtrack alone: no frames, so no sink; the job writes it (WavWriter).
bool is_wav(const std::string& path) { return extension_of(path) == ".wav"; }

const Error container_for_files{"a container is chosen for standard output (-o -) or a segment "
                                "(--segment) only; a file's extension picks its format"};

struct Resolved {
    const OutputKind* kind = nullptr;
    std::optional<FramePattern> pattern;   // a PNG sequence
};

Expected<Resolved> resolve(const std::string& path) {
    const std::string extension = extension_of(path);
    const auto kind = std::find_if(output_kinds.begin(), output_kinds.end(),
                                   [&](const OutputKind& k) { return k.name == extension; });
    if (kind == output_kinds.end()) {
        if (extension.empty()) {
            return Error{"output '" + path + "' has no extension (supported: " +
                         supported_formats() + ")"};
        }
        return Error{"unsupported output extension '" + extension + "' (supported: " +
                     supported_formats() + ")"};
    }
    Resolved resolved{&*kind, std::nullopt};
    if (kind->video == nullptr) {
        auto pattern = parse_frame_pattern(path);
        if (!pattern) {
            return pattern.error();
        }
        resolved.pattern = std::move(*pattern);
    }
    return resolved;
}

Status check_resolved(const Resolved& resolved, const SinkDef& def) {
    if (!def.stream_container.empty() && resolved.kind->name != "-") {
        return container_for_files;
    }
    if (resolved.kind->video != nullptr) {
        auto format = resolved.kind->video(def);
        if (!format) {
            return format.error();
        }
        return {};
    }
    return reject_encoder_settings(def, "PNG");
}

}  // namespace

Expected<OutputDescription> describe_output(const std::string& path,
                                            const std::string& stream_container) {
    if (is_wav(path)) {
        if (!stream_container.empty()) {
            return container_for_files;
        }
        OutputDescription description;
        description.path = path;
        description.format = "wav";
        return description;
    }
    auto resolved = resolve(path);
    if (!resolved) {
        return resolved.error();
    }
    OutputDescription description;
    description.path = path;
    description.format = std::string(resolved->kind->format);
    description.to_stdout = path == "-";
    if (description.to_stdout && !stream_container.empty()) description.format = stream_container;
    if (resolved->kind->video == nullptr) {
        description.one_frame = !resolved->pattern.has_value();
        description.alpha = true;
        if (resolved->pattern) {
            description.format = "png sequence";
        }
    }
    return description;
}

std::string OutputDescription::frame_path(int n) const {
    const auto pattern = parse_frame_pattern(path);
    return pattern && *pattern ? (*pattern)->path_of(n) : path;
}

Status check_settings(const SinkDef& def) {
    if (is_wav(def.path)) {
        if (!def.stream_container.empty()) {
            return container_for_files;
        }
        return reject_encoder_settings(def, "WAV (the soundtrack alone)");
    }
    auto resolved = resolve(def.path);
    if (!resolved) {
        return resolved.error();
    }
    return check_resolved(*resolved, def);
}

Expected<VideoFormat> container_of(const std::string& path) {
    auto resolved = resolve(path);
    if (!resolved) return resolved.error();
    const std::string_view name = resolved->kind->name;
    if (name != ".mp4" && name != ".mkv" && name != ".webm") {
        return Error{"segments join into .mp4, .mkv or .webm files, not '" + path + "'"};
    }
    SinkDef def;
    def.path = path;
    return resolved->kind->video(def);
}

Status Sink::write_sound(std::span<const std::int16_t>) {
    return Error{"this output carries no sound"};
}

Status Sink::finish() {
    if (Status sealed = seal(); !sealed) return sealed;
    return commit_together(files());
}

Expected<std::unique_ptr<Sink>> open_sink(const SinkDef& def) {
    if (is_wav(def.path)) {
        return write_error(def.path, "a .wav holds sound, not frames (encode::WavWriter)");
    }
    auto resolved = resolve(def.path);
    if (!resolved) {
        return resolved.error();
    }
    if (resolved->kind->video != nullptr) {
        auto format = resolved->kind->video(def);
        if (!format) {
            return write_error(def.path, format.error().message);
        }
        return open_video_sink(def, *format);
    }
    if (auto status = check_resolved(*resolved, def); !status) {
        return write_error(def.path, status.error().message);
    }
    if (resolved->pattern) {
        return open_png_sequence_sink(def, std::move(*resolved->pattern));
    }
    return open_png_still_sink(def);
}

}  // namespace discreel::encode
