#include "video_format.hpp"

#include <algorithm>
#include <array>
#include <string_view>

namespace discreel::encode {
namespace {

constexpr std::array<std::string_view, 10> x264_presets = {
    "ultrafast", "superfast", "veryfast", "faster", "fast",
    "medium",    "slow",      "slower",   "veryslow", "placebo"};

template <std::size_t N>
std::string joined(const std::array<std::string_view, N>& words) {
    std::string list;
    for (const auto word : words) {
        list += (list.empty() ? "" : ", ") + std::string(word);
    }
    return list;
}

Error not_applicable(const std::string& setting, const std::string& target) {
    return Error{setting + " does not apply to " + target};
}

// x264's AVX-512 routines make its bytes depend on memory it has not written: two encodes of
// the same frames with the same settings in one process came out different on an AVX-512
// machine (libx264 0.164.3095), and never with AVX2 or below, or with x264's C code. Where the
// CPU has AVX-512, x264 is held to its AVX2 routines (the instruction sets every AVX-512 CPU
// has), and elsewhere it picks its own.
std::string_view x264_instruction_sets() {
#if defined(__x86_64__) && defined(__GNUC__)
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx2") &&
        __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi") &&
        __builtin_cpu_supports("bmi2")) {
        return "AVX2";  // x264's name for AVX2 with FMA3, LZCNT, BMI1, BMI2 and all below
    }
#endif
    return {};
}

Status check_threads(const SinkDef& def) {
    if (def.threads < 1) {
        return Error{"encoder threads must be at least 1, got " + std::to_string(def.threads)};
    }
    return {};
}

Status check_crf(const SinkDef& def, int max_crf) {
    if (def.crf && (*def.crf < 0 || *def.crf > max_crf)) {
        return Error{"crf " + std::to_string(*def.crf) + " is outside 0.." +
                     std::to_string(max_crf)};
    }
    return {};
}

// yuv420p halves the colour resolution; yuv444p keeps it, for crisp edges between colours.
Expected<AVPixelFormat> yuv_pixel_format(const SinkDef& def, const std::string& codec_name) {
    if (def.pixel_format.empty() || def.pixel_format == "yuv420p") {
        return AV_PIX_FMT_YUV420P;
    }
    if (def.pixel_format == "yuv444p") {
        return AV_PIX_FMT_YUV444P;
    }
    return Error{"pixel format '" + def.pixel_format + "' is not available for " + codec_name +
                 " (yuv420p, yuv444p)"};
}

Status check_codec(const SinkDef& def, const std::string& extension,
                   std::initializer_list<std::string_view> available) {
    if (def.codec.empty() ||
        std::find(available.begin(), available.end(), def.codec) != available.end()) {
        return {};
    }
    std::string list;
    for (const auto codec : available) {
        list += (list.empty() ? "" : ", ") + std::string(codec);
    }
    return Error{"codec '" + def.codec + "' is not available for " + extension + " (" + list +
                 ")"};
}

Expected<VideoFormat> h264_format(const SinkDef& def, const std::string& muxer) {
    const std::string preset = def.preset.empty() ? "veryfast" : def.preset;
    if (std::find(x264_presets.begin(), x264_presets.end(), preset) == x264_presets.end()) {
        return Error{"unknown x264 preset '" + preset + "' (" + joined(x264_presets) + ")"};
    }
    if (auto status = check_crf(def, 51); !status) {
        return status.error();
    }
    if (auto status = check_threads(def); !status) {
        return status.error();
    }
    auto pixel_format = yuv_pixel_format(def, "H.264");
    if (!pixel_format) {
        return pixel_format.error();
    }
    VideoFormat format;
    format.muxer = muxer;
    format.encoder = "libx264";
    format.pixel_format = *pixel_format;
    // x264's bytes depend on its thread count, so it is pinned rather than left to the core
    // count. Everything else x264 threads by is derived from it: lookahead threads are
    // computed from the thread count, sliced threads stay off (only the zerolatency tune turns
    // them on) and x264 runs in its default deterministic mode.
    format.threads = def.threads;
    format.encoder_options = {{"preset", preset}, {"crf", std::to_string(def.crf.value_or(20))}};
    std::string x264_params;
    const auto add_param = [&](std::string_view name, std::string_view value) {
        if (!x264_params.empty()) x264_params += ':';
        x264_params.append(name).append("=").append(value);
    };
    if (const std::string_view sets = x264_instruction_sets(); !sets.empty()) {
        add_param("asm", sets);
    }
    // Memory above 720p, where x264's input frames dominate the peak (docs/performance.md):
    // sync-lookahead=0 runs x264's lookahead on the calling thread instead of buffering frames
    // for a thread of its own (the same pictures, four input frames less, but with 2 threads the
    // encoder then waits on it, so not at 720p and below, where memory is no concern), and
    // veryfast's 10-frame lookahead is cut to 8 (its frame-type and rate decisions see two
    // frames less). A 1080p render then stays under 300 MB.
    if (static_cast<long>(def.width) * def.height > 1280L * 720L) {
        add_param("sync-lookahead", "0");
        if (preset == "veryfast") add_param("rc-lookahead", "8");
    }
    // A closed group of pictures per segment: one keyframe, at its start, whatever the
    // pictures show.
    if (def.keyint > 0) {
        add_param("keyint", std::to_string(def.keyint));
        add_param("scenecut", "0");
        add_param("open-gop", "0");
    }
    if (!x264_params.empty()) format.encoder_options.push_back({"x264-params", x264_params});
    return format;
}

Expected<VideoFormat> vp9_format(const SinkDef& def, const std::string& muxer) {
    if (!def.preset.empty()) {
        return not_applicable("preset", "VP9 (it is an x264 setting)");
    }
    if (auto status = check_crf(def, 63); !status) {
        return status.error();
    }
    if (auto status = check_threads(def); !status) {
        return status.error();
    }
    auto pixel_format = yuv_pixel_format(def, "VP9");
    if (!pixel_format) {
        return pixel_format.error();
    }
    VideoFormat format;
    format.muxer = muxer;
    format.encoder = "libvpx-vp9";
    format.pixel_format = *pixel_format;
    format.threads = def.threads;
    if (def.keyint > 0) format.gop_size = def.keyint;
    format.encoder_options = {
        // Constant quality: crf with no bitrate target ("b" 0), as libvpx documents it.
        {"crf", std::to_string(def.crf.value_or(32))},
        {"b", "0"},
        // "good" with cpu-used 5 is libvpx's fastest two-pass-quality mode; "realtime" is faster
        // still but drops quality visibly on fast motion.
        {"deadline", "good"},
        {"cpu-used", "5"},
        // Row multithreading schedules work by thread timing; off, the bytes depend only on the
        // (pinned) thread count and the tile layout, which follows from the frame width.
        {"row-mt", "0"},
    };
    return format;
}

// FFV1 on bgr0 stores the RGB of every pixel exactly (alpha dropped: frames are opaque).
Expected<VideoFormat> ffv1_format(const SinkDef& def) {
    if (def.crf) {
        return not_applicable("crf", "FFV1 (lossless)");
    }
    if (!def.preset.empty()) {
        return not_applicable("preset", "FFV1 (lossless)");
    }
    if (!def.pixel_format.empty()) {
        return not_applicable("pixel format", "FFV1 (lossless, it stores RGB as bgr0)");
    }
    if (auto status = check_threads(def); !status) {
        return status.error();
    }
    VideoFormat format;
    format.muxer = "matroska";
    format.encoder = "ffv1";
    format.pixel_format = AV_PIX_FMT_0RGB32;   // FFV1's native-endian RGB: bgr0 in memory order
    format.colorspace = AVCOL_SPC_RGB;
    format.transfer = AVCOL_TRC_IEC61966_2_1;   // sRGB, which the frames are
    format.range = AVCOL_RANGE_JPEG;
    // Version 3 codes slices independently with a CRC each; the slice layout is fixed (2x2)
    // whatever the thread count, so the bytes do not depend on it; it is pinned all the same.
    format.threads = def.threads;
    format.encoder_options = {{"level", "3"}, {"slicecrc", "1"}};
    return format;
}

}  // namespace

Status reject_encoder_settings(const SinkDef& def, const std::string& target) {
    if (def.crf) return not_applicable("crf", target);
    if (!def.preset.empty()) return not_applicable("preset", target);
    if (!def.codec.empty()) return not_applicable("codec", target);
    if (!def.pixel_format.empty()) return not_applicable("pixel format", target);
    if (def.lossless) return not_applicable("lossless", target);
    return {};
}

namespace {

// H.264 in MP4, a file or a stream; only the lossless advice, the name the codec error uses
// and the muxer's movflags differ between them.
Expected<VideoFormat> h264_in_mp4(const SinkDef& def, const std::string& lossless_advice,
                                  const std::string& output_name, const std::string& movflags) {
    if (def.lossless) {
        return Error{"lossless output is FFV1 in Matroska: " + lossless_advice};
    }
    if (auto status = check_codec(def, output_name, {"h264"}); !status) {
        return status.error();
    }
    auto format = h264_format(def, "mp4");
    if (format) {
        format->muxer_options = {{"movflags", movflags}};
    }
    return format;
}

}  // namespace

Expected<VideoFormat> mp4_format(const SinkDef& def) {
    return h264_in_mp4(def, "use .mkv or -, not .mp4", ".mp4", "+faststart");
}

Expected<VideoFormat> stream_format(const SinkDef& def) {
    if (def.stream_container.empty() || def.stream_container == "mkv") return mkv_format(def);
    if (def.stream_container != "mp4") {
        return Error{"unknown stream container '" + def.stream_container + "' (mkv, mp4)"};
    }
    // A pipe cannot seek back to put the index first: an empty moov goes up front and each
    // fragment (one per keyframe) carries its own index, so readers can play the stream as it
    // arrives.
    return h264_in_mp4(def, "stream it as mkv, not mp4", "an mp4 stream",
                       "frag_keyframe+empty_moov+default_base_moof");
}

Expected<VideoFormat> mkv_format(const SinkDef& def) {
    if (auto status = check_codec(def, ".mkv", {"h264", "vp9", "ffv1"}); !status) {
        return status.error();
    }
    if (def.lossless && !def.codec.empty() && def.codec != "ffv1") {
        return Error{"lossless output is FFV1; it cannot be combined with codec '" + def.codec +
                     "'"};
    }
    if (def.lossless || def.codec == "ffv1") {
        return ffv1_format(def);
    }
    if (def.codec == "vp9") {
        return vp9_format(def, "matroska");
    }
    return h264_format(def, "matroska");
}

Expected<VideoFormat> webm_format(const SinkDef& def) {
    if (def.lossless) {
        return Error{"lossless output is FFV1 in Matroska: use .mkv or -, not .webm"};
    }
    if (auto status = check_codec(def, ".webm", {"vp9"}); !status) {
        return status.error();
    }
    return vp9_format(def, "webm");
}

Expected<VideoFormat> gif_format(const SinkDef& def) {
    if (auto status = reject_encoder_settings(def, "GIF"); !status) {
        return status.error();
    }
    VideoFormat format;
    format.muxer = "gif";
    format.encoder = "gif";
    format.pixel_format = AV_PIX_FMT_PAL8;
    // GIF carries no colour tags: its palette entries are sRGB by convention.
    format.colorspace = AVCOL_SPC_UNSPECIFIED;
    format.primaries = AVCOL_PRI_UNSPECIFIED;
    format.transfer = AVCOL_TRC_UNSPECIFIED;
    format.range = AVCOL_RANGE_UNSPECIFIED;
    format.threads = 1;
    return format;
}

}  // namespace discreel::encode
