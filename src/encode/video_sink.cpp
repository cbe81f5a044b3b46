#include "video_sink.hpp"

#include <optional>
#include <string>
#include <utility>

extern "C" {
#include <libavutil/opt.h>
#include <libavutil/pixdesc.h>
}

#include "av_handles.hpp"
#include "frame_converter.hpp"
#include "image_check.hpp"
#include "libav_log.hpp"
#include "sound_track.hpp"
#include "discreel/output_file.hpp"

namespace discreel::encode {
namespace {

std::string size_text(int width, int height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

// Builds an AVDictionary for one libav call and frees whatever the call did not consume.
class Options {
public:
    explicit Options(const OptionList& options) {
        for (const auto& [key, value] : options) {
            av_dict_set(&dictionary_, key.c_str(), value.c_str(), 0);
        }
    }
    Options(const Options&) = delete;
    Options& operator=(const Options&) = delete;
    ~Options() { av_dict_free(&dictionary_); }

    AVDictionary** get() { return &dictionary_; }
    // Options the callee did not recognise, e.g. "tune"; empty when all were applied.
    std::string unused() const {
        std::string keys;
        const AVDictionaryEntry* entry = nullptr;
        while ((entry = av_dict_get(dictionary_, "", entry, AV_DICT_IGNORE_SUFFIX)) != nullptr) {
            keys += (keys.empty() ? "" : ", ") + std::string(entry->key);
        }
        return keys;
    }

private:
    AVDictionary* dictionary_ = nullptr;
};

class VideoSink final : public Sink {
public:
    VideoSink(const SinkDef& def, std::optional<OutputFile> file,
              std::unique_ptr<FrameConverter> converter,
              OutputFormatContextPtr muxer, CodecContextPtr encoder, AVStream* stream,
              FramePtr frame, PacketPtr packet)
        : def_(def),
          file_(std::move(file)),
          converter_(std::move(converter)),
          muxer_(std::move(muxer)),
          encoder_(std::move(encoder)),
          stream_(stream),
          frame_(std::move(frame)),
          packet_(std::move(packet)) {}

    Status write(const ImageView& frame) override;
    Status write_sound(std::span<const std::int16_t> samples) override;
    Status seal() override;
    void set_sound(SoundTrack track) { sound_.emplace(std::move(track)); }
    std::vector<OutputFile*> files() override {
        if (!file_) return {};
        return {&*file_};
    }

private:
    Error failure(const std::string& what, int error_code) {
        failed_ = true;
        return write_error(def_.path, what + ": " + libav_reason(error_code));
    }
    Status usable() const;
    // Sends one frame (nullptr to flush) and writes every packet the encoder has ready.
    Status encode(const AVFrame* frame);

    SinkDef def_;
    // Declared first: destroyed last, after libav has closed the file. None for standard output.
    std::optional<OutputFile> file_;
    std::unique_ptr<FrameConverter> converter_;
    OutputFormatContextPtr muxer_;
    CodecContextPtr encoder_;
    AVStream* stream_;  // owned by muxer_
    FramePtr frame_;    // reused for every frame, made writable before each fill
    PacketPtr packet_;
    std::optional<SoundTrack> sound_;   // the second stream, with SinkDef::sound
    std::int64_t frames_written_ = 0;
    bool finished_ = false;
    bool failed_ = false;
};

Status VideoSink::usable() const {
    if (finished_) {
        return write_error(def_.path, "the sink is already finished");
    }
    if (failed_) {
        return write_error(def_.path, "the sink failed earlier and cannot continue");
    }
    return {};
}

Status VideoSink::write(const ImageView& frame) {
    begin_libav_call();
    if (auto status = usable(); !status) {
        return status;
    }
    if (auto problem = image_problem(frame)) {
        return write_error(def_.path, *problem);
    }
    if (frame.width != def_.width || frame.height != def_.height) {
        return write_error(def_.path, "frame is " + size_text(frame.width, frame.height) +
                                          " but the video is " +
                                          size_text(def_.width, def_.height));
    }
    // The encoder may still hold a reference to the previous frame's buffers (lookahead).
    if (const int result = av_frame_make_writable(frame_.get()); result < 0) {
        return failure("cannot reuse the frame buffer", result);
    }
    converter_->convert(frame, *frame_);
    frame_->pts = frames_written_;   // encoder time base is 1/fps: pts counts frames
    if (auto status = encode(frame_.get()); !status) {
        return status;
    }
    ++frames_written_;
    // The sound keeps pace with the pictures, so the muxer holds few packets back.
    if (sound_) return sound_->write_until(static_cast<double>(frames_written_) / def_.fps);
    return {};
}

Status VideoSink::write_sound(std::span<const std::int16_t> samples) {
    if (auto status = usable(); !status) return status;
    if (!sound_) return write_error(def_.path, "this output was opened without sound");
    begin_libav_call();
    sound_->push(samples);
    if (Status written = sound_->write_until(static_cast<double>(frames_written_) / def_.fps);
        !written) {
        failed_ = true;
        return write_error(def_.path, written.error().message);
    }
    return {};
}

Status VideoSink::encode(const AVFrame* frame) {
    if (const int result = avcodec_send_frame(encoder_.get(), frame); result < 0) {
        return failure("the encoder rejected a frame", result);
    }
    for (;;) {
        const int result = avcodec_receive_packet(encoder_.get(), packet_.get());
        if (result == AVERROR(EAGAIN) || result == AVERROR_EOF) {
            return {};
        }
        if (result < 0) {
            return failure("encoding failed", result);
        }
        // The muxer chose its own stream time base in avformat_write_header.
        av_packet_rescale_ts(packet_.get(), encoder_->time_base, stream_->time_base);
        packet_->stream_index = stream_->index;
        // Takes ownership of the packet's data and leaves packet_ blank for the next one.
        if (const int written = av_interleaved_write_frame(muxer_.get(), packet_.get());
            written < 0) {
            return failure("writing a packet failed", written);
        }
    }
}

Status VideoSink::seal() {
    begin_libav_call();
    if (auto status = usable(); !status) {
        return status;
    }
    if (frames_written_ == 0) {
        failed_ = true;
        return write_error(def_.path, "no frames were written");
    }
    if (auto status = encode(nullptr); !status) {
        return status;
    }
    if (sound_) {
        if (Status done = sound_->finish(); !done) {
            failed_ = true;
            return write_error(def_.path, done.error().message);
        }
    }
    // Without the trailer an MP4 has no index and does not play.
    if (const int result = av_write_trailer(muxer_.get()); result < 0) {
        return failure("writing the trailer failed", result);
    }
    if (const int result = avio_closep(&muxer_->pb); result < 0) {
        return failure("closing the file failed", result);
    }
    finished_ = true;
    return file_ ? file_->seal() : Status{};
}

}  // namespace

Expected<std::unique_ptr<Sink>> open_video_sink(const SinkDef& def, const VideoFormat& format) {
    begin_libav_call();
    const auto fail = [&](const std::string& what, int error_code) {
        return write_error(def.path, what + ": " + libav_reason(error_code));
    };
    if (def.width <= 0 || def.height <= 0) {
        return write_error(def.path, "video size " + size_text(def.width, def.height) +
                                         " is empty");
    }
    const AVPixFmtDescriptor* pixel_format = av_pix_fmt_desc_get(format.pixel_format);
    const int chroma_width_step = 1 << pixel_format->log2_chroma_w;
    const int chroma_height_step = 1 << pixel_format->log2_chroma_h;
    if (def.width % chroma_width_step != 0 || def.height % chroma_height_step != 0) {
        return write_error(def.path, std::string(pixel_format->name) +
                                         " video needs an even width and height, got " +
                                         size_text(def.width, def.height));
    }
    if (def.fps <= 0) {
        return write_error(def.path, "fps must be positive, got " + std::to_string(def.fps));
    }
    const AVCodec* codec = avcodec_find_encoder_by_name(format.encoder.c_str());
    if (codec == nullptr) {
        return write_error(def.path, "libavcodec has no encoder '" + format.encoder + "'");
    }

    // "-" is standard output: a pipe cannot seek, so the muxer writes a stream that needs no
    // going back (Matroska with unknown-size clusters and no index). There is no temporary
    // file to rename: the bytes leave as they are encoded.
    const bool to_stdout = def.path == "-";
    std::optional<OutputFile> file;
    if (!to_stdout) {
        auto created = OutputFile::create(def.path);
        if (!created) {
            return created.error();
        }
        file.emplace(std::move(*created));
    }
    const std::string io_url = to_stdout ? std::string("pipe:1") : file->temp_path();

    AVFormatContext* raw_muxer = nullptr;
    if (const int result = avformat_alloc_output_context2(
            &raw_muxer, nullptr, format.muxer.c_str(), io_url.c_str());
        result < 0) {
        return fail("cannot set up the " + format.muxer + " muxer", result);
    }
    OutputFormatContextPtr muxer(raw_muxer);
    // No library version strings (and, for Matroska, no random ids): same input, same bytes.
    muxer->flags |= AVFMT_FLAG_BITEXACT;

    CodecContextPtr encoder(avcodec_alloc_context3(codec));
    FramePtr frame(av_frame_alloc());
    PacketPtr packet(av_packet_alloc());
    if (!encoder || !frame || !packet) {
        return fail("cannot allocate the encoder", AVERROR(ENOMEM));
    }
    encoder->width = def.width;
    encoder->height = def.height;
    encoder->pix_fmt = format.pixel_format;
    encoder->time_base = AVRational{1, def.fps};
    encoder->framerate = AVRational{def.fps, 1};
    encoder->colorspace = format.colorspace;
    encoder->color_primaries = format.primaries;
    encoder->color_trc = format.transfer;
    encoder->color_range = format.range;
    encoder->thread_count = format.threads;
    if (format.gop_size > 0) encoder->gop_size = format.gop_size;
    encoder->flags |= AV_CODEC_FLAG_BITEXACT;
    // MP4 and Matroska keep the codec headers (SPS/PPS) in the container, not in the stream.
    if (muxer->oformat->flags & AVFMT_GLOBALHEADER) {
        encoder->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    }
    Options encoder_options(format.encoder_options);
    if (const int result = avcodec_open2(encoder.get(), codec, encoder_options.get());
        result < 0) {
        return fail("cannot open the " + format.encoder + " encoder", result);
    }
    if (const auto unused = encoder_options.unused(); !unused.empty()) {
        return write_error(def.path, format.encoder + " does not know the options " + unused);
    }

    AVStream* stream = avformat_new_stream(muxer.get(), nullptr);
    if (stream == nullptr) {
        return fail("cannot add a video stream", AVERROR(ENOMEM));
    }
    stream->time_base = encoder->time_base;   // a hint; the muxer may choose another
    stream->avg_frame_rate = encoder->framerate;
    if (const int result = avcodec_parameters_from_context(stream->codecpar, encoder.get());
        result < 0) {
        return fail("cannot describe the video stream", result);
    }

    if (const int result = avio_open(&muxer->pb, io_url.c_str(), AVIO_FLAG_WRITE); result < 0) {
        return fail(to_stdout ? std::string("cannot open standard output")
                              : "cannot open the temporary file '" + io_url + "'",
                    result);
    }
    std::optional<SoundTrack> sound;
    if (def.sound) {
        auto added = SoundTrack::add(*muxer, format.muxer == "webm" ? "webm" : "mp4");
        if (!added) return write_error(def.path, added.error().message);
        sound.emplace(std::move(*added));
    }
    Options muxer_options(format.muxer_options);
    if (const int result = avformat_write_header(muxer.get(), muxer_options.get()); result < 0) {
        return fail("cannot write the " + format.muxer + " header", result);
    }
    if (const auto unused = muxer_options.unused(); !unused.empty()) {
        return write_error(def.path, format.muxer + " does not know the options " + unused);
    }

    frame->format = format.pixel_format;
    frame->width = def.width;
    frame->height = def.height;
    if (const int result = av_frame_get_buffer(frame.get(), 0); result < 0) {
        return fail("cannot allocate a frame", result);
    }
    auto converter = make_frame_converter(def, format);
    if (!converter) {
        return write_error(def.path, converter.error().message);
    }
    auto sink = std::make_unique<VideoSink>(def, std::move(file), std::move(*converter),
                                            std::move(muxer), std::move(encoder), stream,
                                            std::move(frame), std::move(packet));
    if (sound) sink->set_sound(std::move(*sound));
    return std::unique_ptr<Sink>(std::move(sink));
}

}  // namespace discreel::encode
