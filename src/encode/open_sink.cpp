// Sink selection: the extension of the output path names the format.
#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <string_view>

#include "discreel/encode.hpp"
#include "png_still_sink.hpp"
#include "video_format.hpp"
#include "video_sink.hpp"

namespace discreel::encode {
namespace {

using SinkOpener = Expected<std::unique_ptr<Sink>> (*)(const SinkDef&);

struct SinkKind {
    std::string_view extension;   // lower case, with the dot
    SinkOpener open;
};

Expected<std::unique_ptr<Sink>> open_mp4(const SinkDef& def) {
    auto format = mp4_h264_format(def);
    if (!format) {
        return format.error();
    }
    return open_video_sink(def, *format);
}

// A new container or codec is a VideoFormat builder plus one row here.
constexpr std::array<SinkKind, 2> sink_kinds = {{
    {".mp4", open_mp4},
    {".png", open_png_still_sink},
}};

std::string supported_extensions() {
    std::string list;
    for (const auto& kind : sink_kinds) {
        list += (list.empty() ? "" : ", ") + std::string(kind.extension);
    }
    return list;
}

}  // namespace

Expected<std::unique_ptr<Sink>> open_sink(const SinkDef& def) {
    std::string extension = std::filesystem::path(def.path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    const auto kind = std::find_if(sink_kinds.begin(), sink_kinds.end(),
                                   [&](const SinkKind& k) { return k.extension == extension; });
    if (kind == sink_kinds.end()) {
        if (extension.empty()) {
            return Error{"output '" + def.path + "' has no extension (supported: " +
                         supported_extensions() + ")"};
        }
        return Error{"unsupported output extension '" + extension + "' (supported: " +
                     supported_extensions() + ")"};
    }
    return kind->open(def);
}

}  // namespace discreel::encode
