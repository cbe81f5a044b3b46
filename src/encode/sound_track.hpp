#pragma once
// A soundtrack encoded as a video file's second stream: AAC (FFmpeg's native encoder) for MP4
// and Matroska, Opus (libopus) for WebM, from 48 kHz stereo 16-bit PCM read from WAV files in
// order, as one continuous stream. Bit-exact flags and one thread, so the same samples give
// the same packets.
#include <memory>
#include <string>
#include <vector>

#include "av_handles.hpp"
#include "discreel/expected.hpp"

namespace discreel::encode {

class SoundTrack {
public:
    // Adds the stream to `muxer` (before its header is written); `format` is "mp4", "mkv" or
    // "webm". The WAV files are read as the track is written.
    static Expected<SoundTrack> add(AVFormatContext& muxer, const std::string& format,
                                    std::vector<std::string> wav_paths);
    ~SoundTrack();
    SoundTrack(SoundTrack&&) noexcept;
    SoundTrack& operator=(SoundTrack&&) noexcept;

    // Encodes and writes (interleaved) the packets of the samples before `seconds`; with
    // `seconds` past the end, all of them, and the encoder's last packets.
    Status write_until(double seconds);
    Status finish();

private:
    struct Impl;
    explicit SoundTrack(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace discreel::encode
