// SoundTrack: PCM from WAV files -> AAC or Opus -> the muxer, after FFmpeg's
// doc/examples/mux.c audio path.
#include "sound_track.hpp"

#include <cmath>
#include <cstring>
#include <limits>

extern "C" {
#include <libavutil/channel_layout.h>
}

#include "libav_log.hpp"

namespace discreel::encode {
namespace {

constexpr int sample_rate = 48000;
constexpr int channels = 2;

struct InputDeleter {
    void operator()(AVFormatContext* context) const { avformat_close_input(&context); }
};
using InputPtr = std::unique_ptr<AVFormatContext, InputDeleter>;

}  // namespace

struct SoundTrack::Impl {
    AVFormatContext* muxer = nullptr;   // the join's
    AVStream* stream = nullptr;         // owned by muxer
    CodecContextPtr encoder;
    FramePtr frame;
    PacketPtr packet;
    PacketPtr read;
    std::vector<std::string> paths;
    std::size_t next_path = 0;
    InputPtr input;                     // the WAV being read
    std::vector<std::int16_t> pending;  // interleaved samples read, not yet encoded
    std::int64_t sent = 0;              // sample frames given to the encoder
    bool input_done = false;
    bool flushed = false;

    Error failure(const std::string& what, int code) const {
        return Error{"cannot encode the sound: " + what + ": " + libav_reason(code)};
    }

    // Reads at least `frames` sample frames into `pending`, or everything that is left.
    Status fill(std::size_t frames) {
        while (!input_done && pending.size() < frames * channels) {
            if (!input) {
                if (next_path == paths.size()) {
                    input_done = true;
                    break;
                }
                const std::string& path = paths[next_path++];
                AVFormatContext* raw = nullptr;
                if (const int result = avformat_open_input(&raw, path.c_str(), nullptr, nullptr);
                    result < 0) {
                    return Error{"cannot read the sound '" + path + "': " + libav_reason(result)};
                }
                input.reset(raw);
                const AVCodecParameters* p = input->streams[0]->codecpar;
                if (input->nb_streams != 1 || p->codec_id != AV_CODEC_ID_PCM_S16LE ||
                    p->sample_rate != sample_rate || p->ch_layout.nb_channels != channels) {
                    return Error{"the sound '" + path + "' is not 48 kHz stereo 16-bit PCM"};
                }
            }
            const int result = av_read_frame(input.get(), read.get());
            if (result == AVERROR_EOF) {
                input.reset();
                continue;
            }
            if (result < 0) return failure("reading the samples failed", result);
            const std::size_t count = static_cast<std::size_t>(read->size) / sizeof(std::int16_t);
            const std::size_t at = pending.size();
            pending.resize(at + count);
            std::memcpy(pending.data() + at, read->data, count * sizeof(std::int16_t));
            av_packet_unref(read.get());
        }
        return {};
    }

    // Sends one frame (nullptr: the end) and writes every packet the encoder has ready.
    Status send(const AVFrame* f) {
        if (const int result = avcodec_send_frame(encoder.get(), f); result < 0) {
            return failure("the encoder rejected the samples", result);
        }
        for (;;) {
            const int result = avcodec_receive_packet(encoder.get(), packet.get());
            if (result == AVERROR(EAGAIN) || result == AVERROR_EOF) return {};
            if (result < 0) return failure("encoding failed", result);
            av_packet_rescale_ts(packet.get(), encoder->time_base, stream->time_base);
            packet->stream_index = stream->index;
            if (const int written = av_interleaved_write_frame(muxer, packet.get()); written < 0) {
                return failure("writing a packet failed", written);
            }
        }
    }

    Status encode_frame(std::size_t frames) {
        if (const int result = av_frame_make_writable(frame.get()); result < 0) {
            return failure("cannot reuse the frame", result);
        }
        frame->nb_samples = static_cast<int>(frames);
        if (encoder->sample_fmt == AV_SAMPLE_FMT_FLTP) {
            auto* left = reinterpret_cast<float*>(frame->data[0]);
            auto* right = reinterpret_cast<float*>(frame->data[1]);
            for (std::size_t i = 0; i < frames; ++i) {
                left[i] = static_cast<float>(pending[2 * i]) / 32768.0f;
                right[i] = static_cast<float>(pending[2 * i + 1]) / 32768.0f;
            }
        } else {
            std::memcpy(frame->data[0], pending.data(), frames * channels * sizeof(std::int16_t));
        }
        frame->pts = sent;
        pending.erase(pending.begin(),
                      pending.begin() + static_cast<std::ptrdiff_t>(frames * channels));
        sent += static_cast<std::int64_t>(frames);
        return send(frame.get());
    }
};

SoundTrack::SoundTrack(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
SoundTrack::~SoundTrack() = default;
SoundTrack::SoundTrack(SoundTrack&&) noexcept = default;
SoundTrack& SoundTrack::operator=(SoundTrack&&) noexcept = default;

Expected<SoundTrack> SoundTrack::add(AVFormatContext& muxer, const std::string& format,
                                     std::vector<std::string> wav_paths) {
    begin_libav_call();
    auto impl = std::make_unique<Impl>();
    impl->muxer = &muxer;
    impl->paths = std::move(wav_paths);
    // WebM carries Opus (or Vorbis); MP4 and Matroska players expect AAC.
    const bool opus = format == "webm";
    const char* name = opus ? "libopus" : "aac";
    const AVCodec* codec = avcodec_find_encoder_by_name(name);
    if (codec == nullptr) return Error{std::string("libavcodec has no encoder '") + name + "'"};
    impl->encoder.reset(avcodec_alloc_context3(codec));
    impl->frame.reset(av_frame_alloc());
    impl->packet.reset(av_packet_alloc());
    impl->read.reset(av_packet_alloc());
    if (!impl->encoder || !impl->frame || !impl->packet || !impl->read) {
        return impl->failure("cannot allocate the encoder", AVERROR(ENOMEM));
    }
    AVCodecContext& e = *impl->encoder;
    e.sample_fmt = opus ? AV_SAMPLE_FMT_S16 : AV_SAMPLE_FMT_FLTP;
    e.sample_rate = sample_rate;
    e.bit_rate = opus ? 128000 : 160000;
    av_channel_layout_default(&e.ch_layout, channels);
    e.time_base = AVRational{1, sample_rate};
    e.thread_count = 1;
    e.flags |= AV_CODEC_FLAG_BITEXACT;
    if (muxer.oformat->flags & AVFMT_GLOBALHEADER) e.flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    if (const int result = avcodec_open2(&e, codec, nullptr); result < 0) {
        return impl->failure(std::string("cannot open the ") + name + " encoder", result);
    }
    impl->stream = avformat_new_stream(&muxer, nullptr);
    if (impl->stream == nullptr) return impl->failure("cannot add a stream", AVERROR(ENOMEM));
    impl->stream->time_base = e.time_base;
    if (const int result = avcodec_parameters_from_context(impl->stream->codecpar, &e);
        result < 0) {
        return impl->failure("cannot describe the stream", result);
    }
    AVFrame& f = *impl->frame;
    f.format = e.sample_fmt;
    f.nb_samples = e.frame_size;
    if (const int result = av_channel_layout_copy(&f.ch_layout, &e.ch_layout); result < 0) {
        return impl->failure("cannot set up a frame", result);
    }
    f.sample_rate = sample_rate;
    if (const int result = av_frame_get_buffer(&f, 0); result < 0) {
        return impl->failure("cannot allocate a frame", result);
    }
    return SoundTrack(std::move(impl));
}

Status SoundTrack::write_until(double seconds) {
    Impl& s = *impl_;
    begin_libav_call();
    const double limit = std::min(seconds * sample_rate, 9e18);
    const auto frame_size = static_cast<std::size_t>(s.encoder->frame_size);
    while (!s.flushed && static_cast<double>(s.sent) < limit) {
        if (Status filled = s.fill(frame_size); !filled) return filled;
        const std::size_t have = s.pending.size() / channels;
        if (have >= frame_size) {
            if (Status sent = s.encode_frame(frame_size); !sent) return sent;
            continue;
        }
        // The end of the samples: the last, shorter frame, then the encoder's delayed packets.
        if (have > 0) {
            if (Status sent = s.encode_frame(have); !sent) return sent;
        }
        s.flushed = true;
        return s.send(nullptr);
    }
    return {};
}

Status SoundTrack::finish() { return write_until(std::numeric_limits<double>::infinity()); }

}  // namespace discreel::encode
