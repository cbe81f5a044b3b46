// Segment files: their names, finding a render's set in a directory, and joining them by
// stream copy (FFmpeg's doc/examples/remux.c, with the timestamps renumbered).
#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <string_view>

#include "av_handles.hpp"
#include "libav_log.hpp"
#include "sound_track.hpp"
#include "video_format.hpp"
#include "discreel/encode.hpp"
#include "discreel/parse_number.hpp"

namespace discreel::encode {
namespace {

constexpr std::string_view prefix = "segment-";
constexpr std::string_view middle = "-of-";
constexpr std::array<std::string_view, 3> segment_formats{"mp4", "mkv", "webm"};

struct ParsedName {
    int index = 0;
    int count = 0;
    std::string format;
};

// The zero-padded numbers of a segment's name: at least four digits.
std::optional<int> whole_number(std::string_view digits) {
    if (digits.size() < 4 || digits[0] == '-') return std::nullopt;
    return parse_whole(digits);
}

// "segment-0003-of-0010.mp4" -> {3, 10, "mp4"}; nullopt for any other name.
std::optional<ParsedName> parse_name(std::string_view name) {
    if (name.substr(0, prefix.size()) != prefix) return std::nullopt;
    name.remove_prefix(prefix.size());
    const auto of = name.find(middle);
    const auto dot = name.rfind('.');
    if (of == std::string_view::npos || dot == std::string_view::npos || dot < of) {
        return std::nullopt;
    }
    const auto index = whole_number(name.substr(0, of));
    const auto count = whole_number(name.substr(of + middle.size(), dot - of - middle.size()));
    const std::string_view format = name.substr(dot + 1);
    if (!index || !count || *index >= *count ||
        std::find(segment_formats.begin(), segment_formats.end(), format) ==
            segment_formats.end()) {
        return std::nullopt;
    }
    return ParsedName{*index, *count, std::string(format)};
}

struct InputDeleter {
    void operator()(AVFormatContext* context) const { avformat_close_input(&context); }
};
using InputPtr = std::unique_ptr<AVFormatContext, InputDeleter>;

Error read_error(const std::string& path, const std::string& reason) {
    return Error{"cannot read segment '" + path + "': " + reason};
}

// One segment, opened: its only stream is video.
struct Segment {
    InputPtr input;
    AVStream* stream = nullptr;   // owned by input
};

Expected<Segment> open_segment(const std::string& path, bool with_stream_info) {
    begin_libav_call();
    AVFormatContext* raw = nullptr;
    if (const int result = avformat_open_input(&raw, path.c_str(), nullptr, nullptr);
        result < 0) {
        return read_error(path, libav_reason(result));
    }
    InputPtr input(raw);
    // The stream's pixel format and frame rate come from its first packets.
    if (with_stream_info) {
        if (const int result = avformat_find_stream_info(input.get(), nullptr); result < 0) {
            return read_error(path, libav_reason(result));
        }
    }
    if (input->nb_streams != 1 ||
        input->streams[0]->codecpar->codec_type != AVMEDIA_TYPE_VIDEO) {
        return read_error(path, "a segment holds exactly one video stream");
    }
    AVStream* stream = input->streams[0];
    return Segment{std::move(input), stream};
}

// The frames per second of a segment's stream, a whole number as discreel writes them.
Expected<int> frame_rate(const std::string& path, const AVStream& stream) {
    AVRational rate = stream.avg_frame_rate;
    if (rate.num <= 0 || rate.den <= 0) rate = stream.r_frame_rate;
    const double fps = rate.den > 0 ? av_q2d(rate) : 0;
    const long whole = std::lround(fps);
    if (!(whole >= 1 && whole <= 1000 && std::abs(fps - static_cast<double>(whole)) < 1e-3)) {
        return read_error(path, "its frame rate is not a whole number of frames per second");
    }
    return static_cast<int>(whole);
}

// What every segment of one render shares; a difference means another render or settings.
struct Signature {
    AVCodecID codec = AV_CODEC_ID_NONE;
    int width = 0, height = 0, format = -1, fps = 0;
    AVColorRange range = AVCOL_RANGE_UNSPECIFIED;
    AVColorPrimaries primaries = AVCOL_PRI_UNSPECIFIED;
    AVColorTransferCharacteristic transfer = AVCOL_TRC_UNSPECIFIED;
    AVColorSpace space = AVCOL_SPC_UNSPECIFIED;
    std::vector<std::uint8_t> extradata;   // the codec's set-up (H.264: SPS and PPS)

    friend bool operator==(const Signature&, const Signature&) = default;
};

Signature signature_of(const AVCodecParameters& p, int fps) {
    Signature s{p.codec_id, p.width, p.height, p.format, fps, p.color_range, p.color_primaries,
                p.color_trc, p.color_space, {}};
    if (p.extradata != nullptr) s.extradata.assign(p.extradata, p.extradata + p.extradata_size);
    return s;
}

// The frame numbers (pts in frames, from 0) of a segment's packets in decode order, checked:
// one packet per frame, every frame 0..n-1 once, a keyframe first.
Expected<std::vector<int>> frame_order(const std::string& path, Segment& segment, int fps) {
    PacketPtr packet(av_packet_alloc());
    if (!packet) return read_error(path, "out of memory");
    std::vector<int> order;
    for (;;) {
        const int result = av_read_frame(segment.input.get(), packet.get());
        if (result == AVERROR_EOF) break;
        if (result < 0) return read_error(path, libav_reason(result));
        const std::int64_t pts = packet->pts;
        const bool key = (packet->flags & AV_PKT_FLAG_KEY) != 0;
        av_packet_unref(packet.get());
        if (pts == AV_NOPTS_VALUE) return read_error(path, "a packet has no time stamp");
        const std::int64_t frame = av_rescale_q_rnd(
            pts, segment.stream->time_base, AVRational{1, fps},
            static_cast<AVRounding>(AV_ROUND_NEAR_INF | AV_ROUND_PASS_MINMAX));
        if (order.empty() && !key) return read_error(path, "it does not start with a keyframe");
        if (frame < 0 || frame > std::numeric_limits<int>::max()) {
            return read_error(path, "a packet's time stamp is out of range");
        }
        order.push_back(static_cast<int>(frame));
    }
    if (order.empty()) return read_error(path, "it holds no frames");
    std::vector<int> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 0; i < sorted.size(); ++i) {
        if (sorted[i] != static_cast<int>(i)) {
            return read_error(path, "its frames are not numbered 0.." +
                                        std::to_string(sorted.size() - 1) + " once each");
        }
    }
    return order;
}

struct Checked {
    Signature signature;
    std::vector<std::vector<int>> orders;   // per segment
    int delay = 0;                          // frames a packet's decoding may precede its showing
};

Expected<Checked> check_segments(const std::vector<std::string>& segments) {
    Checked checked;
    for (std::size_t k = 0; k < segments.size(); ++k) {
        const std::string& path = segments[k];
        auto segment = open_segment(path, true);
        if (!segment) return segment.error();
        auto fps = frame_rate(path, *segment->stream);
        if (!fps) return fps.error();
        const Signature signature = signature_of(*segment->stream->codecpar, *fps);
        if (k == 0) {
            checked.signature = signature;
        } else if (!(signature == checked.signature)) {
            return Error{"segment '" + path + "' was not encoded like '" + segments[0] +
                         "' (codec, size, frame rate or encoder settings differ); join the "
                         "segments of one render"};
        }
        auto order = frame_order(path, *segment, *fps);
        if (!order) return order.error();
        for (std::size_t i = 0; i < order->size(); ++i) {
            checked.delay = std::max(checked.delay, static_cast<int>(i) - (*order)[i]);
        }
        checked.orders.push_back(std::move(*order));
    }
    // Every segment but the last has the render's segment length.
    const std::size_t length = checked.orders.front().size();
    for (std::size_t k = 0; k + 1 < checked.orders.size(); ++k) {
        if (checked.orders[k].size() != length) {
            return Error{"segment '" + segments[k] + "' has " +
                         std::to_string(checked.orders[k].size()) + " frames and '" +
                         segments[0] + "' " + std::to_string(length) +
                         "; only the last segment of a render may be shorter"};
        }
    }
    if (checked.orders.back().size() > length) {
        return Error{"segment '" + segments.back() + "' is longer than the segments before it"};
    }
    return checked;
}

// The sample frames (one per channel pair) of a 48 kHz stereo 16-bit WAV file.
Expected<std::int64_t> sample_frames(const std::string& path) {
    begin_libav_call();
    AVFormatContext* raw = nullptr;
    if (const int result = avformat_open_input(&raw, path.c_str(), nullptr, nullptr);
        result < 0) {
        return Error{"cannot read the sound '" + path + "': " + libav_reason(result)};
    }
    InputPtr input(raw);
    const AVCodecParameters* p = input->nb_streams == 1 ? input->streams[0]->codecpar : nullptr;
    if (p == nullptr || p->codec_id != AV_CODEC_ID_PCM_S16LE ||
        p->sample_rate != SoundTrack::sample_rate || p->ch_layout.nb_channels != 2) {
        return Error{"the sound '" + path + "' is not 48 kHz stereo 16-bit PCM"};
    }
    PacketPtr packet(av_packet_alloc());
    if (!packet) return Error{"cannot read the sound '" + path + "': out of memory"};
    std::int64_t bytes = 0;
    for (;;) {
        const int result = av_read_frame(input.get(), packet.get());
        if (result == AVERROR_EOF) break;
        if (result < 0) {
            return Error{"cannot read the sound '" + path + "': " + libav_reason(result)};
        }
        bytes += packet->size;
        av_packet_unref(packet.get());
    }
    return bytes / 4;
}

// The first sample frame of frame `frame` at `fps` (the soundtrack's own rounding).
std::int64_t sample_of(std::int64_t frame, int fps) {
    const std::int64_t scaled = frame * SoundTrack::sample_rate;
    return (2 * scaled + fps) / (2 * static_cast<std::int64_t>(fps));
}

// Each segment's sound is as long as its frames (or one sound as long as all of them): a
// cut-off file would shift every later sound early against the pictures.
Status check_sounds(const std::vector<std::string>& sounds, const Checked& checked) {
    const int fps = checked.signature.fps;
    std::vector<std::int64_t> frames;
    for (const std::vector<int>& order : checked.orders) {
        frames.push_back(static_cast<std::int64_t>(order.size()));
    }
    if (sounds.size() != frames.size()) {
        std::int64_t all = 0;
        for (const std::int64_t n : frames) all += n;
        frames = {all};
    }
    std::int64_t first = 0;
    for (std::size_t k = 0; k < sounds.size() && k < frames.size(); ++k) {
        const std::int64_t wanted = sample_of(first + frames[k], fps) - sample_of(first, fps);
        auto got = sample_frames(sounds[k]);
        if (!got) return got.error();
        if (*got != wanted) {
            return Error{"the sound '" + sounds[k] + "' holds " + std::to_string(*got) +
                         " samples, and its segment's " + std::to_string(frames[k]) +
                         " frames need " + std::to_string(wanted) + "; render segment " +
                         std::to_string(k) + " again"};
        }
        first += frames[k];
    }
    return {};
}

// The samples of 48 kHz stereo 16-bit WAV files, one after another, fed to a SoundTrack as the
// join needs them.
class WavChunks {
public:
    explicit WavChunks(std::vector<std::string> paths)
        : paths_(std::move(paths)), packet_(av_packet_alloc()) {}

    // Pushes samples into `track` until it holds a little more than those before `seconds`
    // (what its next whole encoder frame needs), or there are no more.
    Status feed(SoundTrack& track, double seconds) {
        const double wanted = seconds * SoundTrack::sample_rate + 4096;
        while (static_cast<double>(track.pushed()) < wanted) {
            if (!input_) {
                if (next_ == paths_.size()) return {};
                const std::string& path = paths_[next_++];
                AVFormatContext* raw = nullptr;
                if (const int result = avformat_open_input(&raw, path.c_str(), nullptr, nullptr);
                    result < 0) {
                    return Error{"cannot read the sound '" + path + "': " + libav_reason(result)};
                }
                input_.reset(raw);
                const AVCodecParameters* p = input_->streams[0]->codecpar;
                if (input_->nb_streams != 1 || p->codec_id != AV_CODEC_ID_PCM_S16LE ||
                    p->sample_rate != SoundTrack::sample_rate || p->ch_layout.nb_channels != 2) {
                    return Error{"the sound '" + path + "' is not 48 kHz stereo 16-bit PCM"};
                }
            }
            const int result = av_read_frame(input_.get(), packet_.get());
            if (result == AVERROR_EOF) {
                input_.reset();
                continue;
            }
            if (result < 0) return Error{"cannot read the sound: " + libav_reason(result)};
            track.push({reinterpret_cast<const std::int16_t*>(packet_->data),
                        static_cast<std::size_t>(packet_->size) / sizeof(std::int16_t)});
            av_packet_unref(packet_.get());
        }
        return {};
    }

private:
    std::vector<std::string> paths_;
    std::size_t next_ = 0;
    InputPtr input_;
    PacketPtr packet_;
};

}  // namespace

std::string segment_file_name(int index, int count, const std::string& format) {
    char text[64];
    std::snprintf(text, sizeof text, "segment-%04d-of-%04d.", index, count);
    return text + format;
}

Expected<SegmentSet> find_segments(const std::string& dir) {
    std::error_code error;
    std::filesystem::directory_iterator entries(dir, error);
    if (error) return Error{"cannot read the directory '" + dir + "': " + error.message()};
    std::map<int, std::string> found;   // index -> path
    std::optional<ParsedName> first;
    for (const auto& entry : entries) {
        const std::string name = entry.path().filename().string();
        const auto parsed = parse_name(name);
        if (!parsed) continue;
        if (!first) {
            first = parsed;
        } else if (parsed->count != first->count || parsed->format != first->format) {
            return Error{"'" + dir + "' holds segments of different renders (" +
                         segment_file_name(first->index, first->count, first->format) + " and " +
                         name + "); give each render its own directory"};
        }
        found[parsed->index] = entry.path().string();
    }
    std::size_t sounds = 0;
    for (const auto& [index, path] : found) {
        sounds += std::filesystem::exists(std::filesystem::path(path).replace_extension(".wav"));
    }
    if (!first) {
        return Error{"'" + dir + "' holds no segments (files named like " +
                     segment_file_name(0, 3, "mp4") + ", written by render --segment K)"};
    }
    SegmentSet set{first->format, {}, {}};
    // Each input a regular file of its own: a FIFO would block the join where no signal ends
    // it, and two names of one file (a link) would join a segment twice.
    std::map<std::pair<dev_t, ino_t>, std::string> seen;
    const auto check_input = [&](const std::string& path) -> Status {
        struct stat info {};
        if (stat(path.c_str(), &info) != 0) {
            return Error{"cannot read '" + path + "': " + std::strerror(errno)};
        }
        if (!S_ISREG(info.st_mode)) {
            return Error{"'" + path + "' is not a regular file; segments and their sounds are "
                         "files that render --segment wrote"};
        }
        const auto [at, added] = seen.emplace(std::pair{info.st_dev, info.st_ino}, path);
        if (!added) {
            return Error{"'" + path + "' and '" + at->second + "' are the same file; each "
                         "segment must be its own"};
        }
        return {};
    };
    for (int k = 0; k < first->count; ++k) {
        const auto it = found.find(k);
        if (it == found.end()) {
            return Error{"'" + dir + "' lacks segment " + std::to_string(k) + " of " +
                         std::to_string(first->count) + " (" +
                         segment_file_name(k, first->count, first->format) +
                         "); render it with --segment " + std::to_string(k)};
        }
        if (Status usable = check_input(it->second); !usable) return usable.error();
        set.paths.push_back(it->second);
        const std::string sound = std::filesystem::path(it->second).replace_extension(".wav");
        if (sounds > 0 && !std::filesystem::exists(sound)) {
            return Error{"'" + dir + "' lacks the sound of segment " + std::to_string(k) + " (" +
                         segment_file_name(k, first->count, "wav") + "); render it again with "
                         "--segment " + std::to_string(k)};
        }
        if (sounds > 0) {
            if (Status usable = check_input(sound); !usable) return usable.error();
            set.sound.push_back(sound);
        }
    }
    return set;
}

Status join_segments(const SegmentSet& set, OutputFile& file) {
    const std::string& path = file.target_path();
    const std::vector<std::string>& segments = set.paths;
    if (segments.empty()) return write_error(path, "there are no segments to join");
    auto container = container_of(path);
    if (!container) return write_error(path, container.error().message);
    auto target = describe_output(path);
    if (!target) return write_error(path, target.error().message);
    if (target->format != set.format) {
        return Error{"the segments are " + set.format + " files; join them into a ." +
                     set.format + " file, not '" + path + "'"};
    }
    auto checked = check_segments(segments);
    if (!checked) return checked.error();
    const int fps = checked->signature.fps;
    if (Status heard = check_sounds(set.sound, *checked); !heard) return heard;

    begin_libav_call();
    const auto fail = [&](const std::string& what, int code) {
        return write_error(path, what + ": " + libav_reason(code));
    };
    AVFormatContext* raw = nullptr;
    if (const int result = avformat_alloc_output_context2(
            &raw, nullptr, container->muxer.c_str(), file.temp_path().c_str());
        result < 0) {
        return fail("cannot set up the " + container->muxer + " muxer", result);
    }
    OutputFormatContextPtr muxer(raw);
    muxer->flags |= AVFMT_FLAG_BITEXACT;
    AVStream* stream = avformat_new_stream(muxer.get(), nullptr);
    if (stream == nullptr) return fail("cannot add a video stream", AVERROR(ENOMEM));
    {
        auto first = open_segment(segments[0], true);
        if (!first) return first.error();
        if (const int result =
                avcodec_parameters_copy(stream->codecpar, first->stream->codecpar);
            result < 0) {
            return fail("cannot describe the video stream", result);
        }
    }
    stream->codecpar->codec_tag = 0;   // the muxer picks its own tag for the codec
    stream->time_base = AVRational{1, fps};
    stream->avg_frame_rate = AVRational{fps, 1};
    if (const int result = avio_open(&muxer->pb, file.temp_path().c_str(), AVIO_FLAG_WRITE);
        result < 0) {
        return fail("cannot open the temporary file", result);
    }
    std::optional<SoundTrack> sound;
    WavChunks samples(set.sound);
    if (!set.sound.empty()) {
        auto added = SoundTrack::add(*muxer, set.format);
        if (!added) return write_error(path, added.error().message);
        sound.emplace(std::move(*added));
    }
    AVDictionary* options = nullptr;
    for (const auto& [key, value] : container->muxer_options) {
        av_dict_set(&options, key.c_str(), value.c_str(), 0);
    }
    const int header = avformat_write_header(muxer.get(), &options);
    av_dict_free(&options);
    if (header < 0) return fail("cannot write the " + container->muxer + " header", header);

    // Packets keep their bytes and keyframe flags; their times are renumbered in frames: the
    // k-th segment's frames follow the frames before it, and decode times trail by the
    // largest reordering any segment showed, so they rise by one frame per packet.
    PacketPtr packet(av_packet_alloc());
    if (!packet) return fail("cannot allocate a packet", AVERROR(ENOMEM));
    std::int64_t first_frame = 0;
    for (std::size_t k = 0; k < segments.size(); ++k) {
        auto segment = open_segment(segments[k], false);
        if (!segment) return segment.error();
        const std::vector<int>& order = checked->orders[k];
        std::size_t i = 0;
        for (;; ++i) {
            const int result = av_read_frame(segment->input.get(), packet.get());
            if (result == AVERROR_EOF) break;
            if (result < 0) return read_error(segments[k], libav_reason(result));
            if (i >= order.size()) return read_error(segments[k], "it changed while being joined");
            const int flags = packet->flags & AV_PKT_FLAG_KEY;
            av_packet_free_side_data(packet.get());
            packet->flags = flags;
            packet->pts = first_frame + order[i];
            packet->dts = first_frame + static_cast<std::int64_t>(i) - checked->delay;
            packet->duration = 1;
            packet->pos = -1;
            packet->stream_index = 0;
            const double decoded_at = static_cast<double>(packet->dts) / fps;
            av_packet_rescale_ts(packet.get(), AVRational{1, fps}, stream->time_base);
            if (const int written = av_interleaved_write_frame(muxer.get(), packet.get());
                written < 0) {
                return fail("writing a packet failed", written);
            }
            // The sound keeps pace with the pictures, so the muxer holds few packets back.
            if (sound) {
                Status kept = samples.feed(*sound, decoded_at);
                if (kept) kept = sound->write_until(decoded_at);
                if (!kept) return write_error(path, kept.error().message);
            }
        }
        if (i != order.size()) return read_error(segments[k], "it changed while being joined");
        first_frame += static_cast<std::int64_t>(order.size());
    }
    if (sound) {
        Status done = samples.feed(*sound, std::numeric_limits<double>::infinity());
        if (done) done = sound->finish();
        if (!done) return write_error(path, done.error().message);
    }
    if (const int result = av_write_trailer(muxer.get()); result < 0) {
        return fail("writing the trailer failed", result);
    }
    if (const int result = avio_closep(&muxer->pb); result < 0) {
        return fail("closing the file failed", result);
    }
    return file.seal();
}

}  // namespace discreel::encode
