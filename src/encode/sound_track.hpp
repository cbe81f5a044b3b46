#pragma once
// A soundtrack encoded as a video file's second stream: AAC (FFmpeg's native encoder) for MP4
// and Matroska, Opus (libopus) for WebM, from 48 kHz stereo 16-bit PCM pushed in blocks of any
// size, as one continuous stream. Bit-exact flags and one thread, so the same samples give the
// same packets however they were cut.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "av_handles.hpp"
#include "discreel/expected.hpp"

namespace discreel::encode {

class SoundTrack {
public:
    static constexpr int sample_rate = 48000;   // the samples pushed: stereo, interleaved
    // Adds the stream to `muxer` (before its header is written); `format` is "mp4", "mkv" or
    // "webm".
    static Expected<SoundTrack> add(AVFormatContext& muxer, const std::string& format);
    ~SoundTrack();
    SoundTrack(SoundTrack&&) noexcept;
    SoundTrack& operator=(SoundTrack&&) noexcept;

    void push(std::span<const std::int16_t> samples);
    std::int64_t pushed() const;   // sample frames pushed so far
    // Encodes and writes (interleaved) the whole encoder frames pushed that start before
    // `seconds`.
    Status write_until(double seconds);
    // Encodes everything pushed (the last frame may be short) and the encoder's last packets.
    Status finish();

private:
    struct Impl;
    explicit SoundTrack(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace discreel::encode
