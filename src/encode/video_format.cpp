#include "video_format.hpp"

#include <algorithm>
#include <array>
#include <string_view>

#include "output_file.hpp"

namespace discreel::encode {
namespace {

constexpr std::array<std::string_view, 10> x264_presets = {
    "ultrafast", "superfast", "veryfast", "faster", "fast",
    "medium",    "slow",      "slower",   "veryslow", "placebo"};

std::string preset_list() {
    std::string list;
    for (const auto preset : x264_presets) {
        list += (list.empty() ? "" : ", ") + std::string(preset);
    }
    return list;
}

}  // namespace

Expected<VideoFormat> mp4_h264_format(const SinkDef& def) {
    if (std::find(x264_presets.begin(), x264_presets.end(), def.preset) == x264_presets.end()) {
        return write_error(def.path,
                           "unknown x264 preset '" + def.preset + "' (" + preset_list() + ")");
    }
    if (def.crf < 0 || def.crf > 51) {
        return write_error(def.path, "crf " + std::to_string(def.crf) + " is outside 0..51");
    }
    if (def.threads < 1) {
        return write_error(def.path, "encoder threads must be at least 1, got " +
                                         std::to_string(def.threads));
    }
    VideoFormat format;
    format.muxer = "mp4";
    format.encoder = "libx264";
    format.pixel_format = AV_PIX_FMT_YUV420P;
    // x264's bytes depend on its thread count, so it is pinned rather than left to the core
    // count. Everything else x264 threads by is derived from it: lookahead threads are
    // computed from the thread count, sliced threads stay off (only the zerolatency tune turns
    // them on) and x264 runs in its default deterministic mode.
    format.threads = def.threads;
    format.encoder_options = {{"preset", def.preset}, {"crf", std::to_string(def.crf)}};
    format.muxer_options = {{"movflags", "+faststart"}};
    return format;
}

}  // namespace discreel::encode
