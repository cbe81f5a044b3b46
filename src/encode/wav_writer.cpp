// WavWriter: PCM samples as packets straight into libavformat's wav muxer (PCM needs no
// encoder: a packet of pcm_s16le is the samples' bytes).
#include <cstring>
#include <optional>

#include "av_handles.hpp"
#include "libav_log.hpp"
#include "discreel/encode.hpp"

namespace discreel::encode {

struct WavWriter::Impl {
    OutputFile file;
    OutputFormatContextPtr muxer;
    AVStream* stream = nullptr;   // owned by muxer
    PacketPtr packet;
    int channels = 2;
    std::int64_t frames_written = 0;
    bool sealed = false;

    Error failure(const std::string& what, int code) const {
        return write_error(file.target_path(), what + ": " + libav_reason(code));
    }
};

WavWriter::WavWriter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
WavWriter::~WavWriter() = default;
WavWriter::WavWriter(WavWriter&&) noexcept = default;
WavWriter& WavWriter::operator=(WavWriter&&) noexcept = default;

Expected<WavWriter> WavWriter::open(const std::string& path, int sample_rate, int channels) {
    begin_libav_call();
    auto file = OutputFile::create(path);
    if (!file) return file.error();
    auto impl = std::make_unique<Impl>(Impl{std::move(*file), nullptr, nullptr, nullptr, channels});
    AVFormatContext* raw = nullptr;
    if (const int result = avformat_alloc_output_context2(&raw, nullptr, "wav",
                                                          impl->file.temp_path().c_str());
        result < 0) {
        return impl->failure("cannot set up the wav muxer", result);
    }
    impl->muxer.reset(raw);
    impl->muxer->flags |= AVFMT_FLAG_BITEXACT;
    impl->stream = avformat_new_stream(raw, nullptr);
    impl->packet.reset(av_packet_alloc());
    if (impl->stream == nullptr || !impl->packet) {
        return impl->failure("cannot add the audio stream", AVERROR(ENOMEM));
    }
    AVCodecParameters* p = impl->stream->codecpar;
    p->codec_type = AVMEDIA_TYPE_AUDIO;
    p->codec_id = AV_CODEC_ID_PCM_S16LE;
    p->sample_rate = sample_rate;
    av_channel_layout_default(&p->ch_layout, channels);
    p->format = AV_SAMPLE_FMT_S16;
    p->bits_per_coded_sample = 16;
    p->block_align = 2 * channels;
    p->bit_rate = static_cast<std::int64_t>(sample_rate) * 16 * channels;
    impl->stream->time_base = AVRational{1, sample_rate};
    if (const int result = avio_open(&raw->pb, impl->file.temp_path().c_str(), AVIO_FLAG_WRITE);
        result < 0) {
        return impl->failure("cannot open the temporary file", result);
    }
    if (const int result = avformat_write_header(raw, nullptr); result < 0) {
        return impl->failure("cannot write the wav header", result);
    }
    return WavWriter(std::move(impl));
}

Status WavWriter::write(std::span<const std::int16_t> samples) {
    Impl& s = *impl_;
    if (samples.empty()) return {};
    begin_libav_call();
    const int bytes = static_cast<int>(samples.size_bytes());
    if (const int result = av_new_packet(s.packet.get(), bytes); result < 0) {
        return s.failure("cannot allocate a packet", result);
    }
    std::memcpy(s.packet->data, samples.data(), samples.size_bytes());   // little-endian hosts
    const auto frames = static_cast<std::int64_t>(samples.size()) / s.channels;
    s.packet->pts = s.packet->dts = s.frames_written;
    s.packet->duration = frames;
    s.packet->stream_index = 0;
    av_packet_rescale_ts(s.packet.get(), AVRational{1, s.stream->codecpar->sample_rate},
                         s.stream->time_base);
    if (const int result = av_write_frame(s.muxer.get(), s.packet.get()); result < 0) {
        av_packet_unref(s.packet.get());
        return s.failure("writing samples failed", result);
    }
    av_packet_unref(s.packet.get());
    s.frames_written += frames;
    return {};
}

Status WavWriter::seal() {
    Impl& s = *impl_;
    begin_libav_call();
    if (const int result = av_write_trailer(s.muxer.get()); result < 0) {
        return s.failure("writing the trailer failed", result);
    }
    if (const int result = avio_closep(&s.muxer->pb); result < 0) {
        return s.failure("closing the file failed", result);
    }
    s.sealed = true;
    return s.file.seal();
}

OutputFile& WavWriter::file() { return impl_->file; }

}  // namespace discreel::encode
