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

constexpr int channels = 2;

}  // namespace

struct SoundTrack::Impl {
    AVFormatContext* muxer = nullptr;   // the join's
    AVStream* stream = nullptr;         // owned by muxer
    CodecContextPtr encoder;
    FramePtr frame;
    PacketPtr packet;
    std::vector<std::int16_t> pending;  // interleaved samples pushed, not yet encoded
    std::int64_t sent = 0;              // sample frames given to the encoder
    std::int64_t pushed = 0;            // sample frames pushed
    bool flushed = false;

    Error failure(const std::string& what, int code) const {
        return Error{"cannot encode the sound: " + what + ": " + libav_reason(code)};
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

Expected<SoundTrack> SoundTrack::add(AVFormatContext& muxer, const std::string& format) {
    begin_libav_call();
    auto impl = std::make_unique<Impl>();
    impl->muxer = &muxer;
    // WebM carries Opus (or Vorbis); MP4 and Matroska players expect AAC.
    const bool opus = format == "webm";
    const char* name = opus ? "libopus" : "aac";
    const AVCodec* codec = avcodec_find_encoder_by_name(name);
    if (codec == nullptr) return Error{std::string("libavcodec has no encoder '") + name + "'"};
    impl->encoder.reset(avcodec_alloc_context3(codec));
    impl->frame.reset(av_frame_alloc());
    impl->packet.reset(av_packet_alloc());
    if (!impl->encoder || !impl->frame || !impl->packet) {
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

void SoundTrack::push(std::span<const std::int16_t> samples) {
    impl_->pending.insert(impl_->pending.end(), samples.begin(), samples.end());
    impl_->pushed += static_cast<std::int64_t>(samples.size() / channels);
}

std::int64_t SoundTrack::pushed() const { return impl_->pushed; }

Status SoundTrack::write_until(double seconds) {
    Impl& s = *impl_;
    begin_libav_call();
    const double limit = std::min(seconds * sample_rate, 9e18);
    const auto frame_size = static_cast<std::size_t>(s.encoder->frame_size);
    while (!s.flushed && static_cast<double>(s.sent) < limit &&
           s.pending.size() >= frame_size * channels) {
        if (Status sent = s.encode_frame(frame_size); !sent) return sent;
    }
    return {};
}

Status SoundTrack::finish() {
    Impl& s = *impl_;
    if (s.flushed) return {};
    if (Status written = write_until(std::numeric_limits<double>::infinity()); !written) {
        return written;
    }
    begin_libav_call();
    // The last, shorter frame, then the encoder's delayed packets.
    if (const std::size_t have = s.pending.size() / channels; have > 0) {
        if (Status sent = s.encode_frame(have); !sent) return sent;
    }
    s.flushed = true;
    return s.send(nullptr);
}

}  // namespace discreel::encode
