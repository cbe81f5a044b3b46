#pragma once
// Frames in, files out (libavformat/libavcodec/libswscale behind this header). A Sink writes to
// temporary files beside its targets (discreel/output_file.hpp) and renames them onto the
// targets only when committed: a sink destroyed before that deletes its temporary files, so the
// target paths hold either the complete new output or whatever was there before. A run with
// several outputs seals the sink and commits its files() together with the others
// (discreel/commit.hpp). The exception is "-" (standard output), which is a stream: bytes leave
// as they are encoded.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "discreel/expected.hpp"
#include "discreel/image.hpp"
#include "discreel/output_file.hpp"

namespace discreel::encode {

using Rgb = std::array<std::uint8_t, 3>;

struct SinkDef {
    std::string path;              // output file; see describe_output for what picks the format
    int width = 1280;              // pixels, even for yuv420p video
    int height = 720;              // pixels, even for yuv420p video
    int fps = 60;                  // frames per second
    std::optional<int> crf;        // quality, lower is better; none: H.264 20 (0..51), VP9 32 (0..63)
    std::string preset;            // x264 preset; empty: veryfast. H.264 only
    int threads = 2;               // encoder threads; pinned, because x264's bytes depend on it
    std::string codec;             // "h264", "vp9", "ffv1"; empty: the format's default
    std::string pixel_format;      // "yuv420p" or "yuv444p" (H.264, VP9); empty: yuv420p
    bool lossless = false;         // FFV1 in Matroska, bit-exact RGB (.mkv and "-" only)
    // The container of a stream to standard output ("-"): "mkv" (default) or "mp4"
    // (fragmented MP4). Files take theirs from the extension.
    std::string stream_container;
    // Colours the frames are mostly made of (the scene's background, walls and discs). A GIF
    // palette starts with them, so they come out exact; other formats ignore them.
    std::vector<Rgb> key_colours;
    // A PNG sequence's number for its first frame: `render --frames 10-20` writes 10..20.
    int first_number = 0;
    // Frames per group of pictures, each opened by a keyframe, with no keyframes in between
    // (x264's scene cuts off): a segment sets its length, so it is one closed group.
    // 0: the encoder's own choice. H.264 and VP9; FFV1 frames are all coded alone.
    int keyint = 0;
    // A second stream, the soundtrack (AAC; Opus in WebM), from samples given to write_sound.
    // Video outputs only.
    bool sound = false;
};

class Sink {
public:
    virtual ~Sink() = default;
    virtual Status write(const ImageView& frame) = 0;   // frames in presentation order
    // With SinkDef::sound: 48 kHz stereo 16-bit samples, interleaved, in order, in blocks of any
    // size; give the sound of each frame before or soon after the frame.
    virtual Status write_sound(std::span<const std::int16_t> samples);
    // Flushes the encoder and closes the output under its temporary name(s): nothing is
    // visible at the target yet.
    virtual Status seal() = 0;
    // After seal(): the files to commit, in order (none for a stream on standard output).
    virtual std::vector<OutputFile*> files() = 0;
    // seal(), then commit_together(files()): for a sink that is its run's only output.
    // A caller may instead move the sealed files out of files() and destroy the sink, which
    // then owns nothing.
    Status finish();
};

// What an output path will be written as.
struct OutputDescription {
    std::string format;            // "mp4", "mkv", "webm", "gif", "png", "png sequence"
    bool one_frame = false;        // a still: the sink takes exactly one frame
    bool to_stdout = false;        // "-": a stream on standard output
    bool alpha = false;            // keeps transparency (PNG); the others are drawn opaque
    // The file of frame n of a "png sequence": "out/frame_%04d.png" -> "out/frame_0012.png".
    std::string frame_path(int n) const;

    std::string path;              // as given
};

// The format an output path names, from the file system's point of view of nothing: "-" is a
// stream on standard output (Matroska, or fragmented MP4 when stream_container is "mp4");
// otherwise the extension, case-insensitive (.mp4, .mkv, .webm,
// .gif, .png); a .png name holding one printf-style frame number (%d, %04d) is a sequence with
// one file per frame, numbered from 0. The error lists the supported formats.
Expected<OutputDescription> describe_output(const std::string& path,
                                            const std::string& stream_container = "");

// Checks the encoder settings of `def` (codec, pixel format, crf, preset, lossless, threads)
// against the format its path names, without touching the file system. The message names the
// setting and says what is allowed; it does not quote the path.
Status check_settings(const SinkDef& def);

// Opens the sink for def.path (see describe_output). Fails for unknown formats, settings that
// check_settings rejects (prefixed "cannot write '<path>': "), odd sizes for yuv420p video,
// missing or unwritable directories and encoders that cannot be opened. Errors name the path.
Expected<std::unique_ptr<Sink>> open_sink(const SinkDef& def);

// Segments: a video encoded in pieces, each its own closed group of pictures in its own file
// (a SinkDef with keyint), joined by stream copy. Segment K of N of a render is the file
// segment_file_name(K, N, format), "segment-0003-of-0010.mp4", so a directory of them says
// which are there and which are missing.
std::string segment_file_name(int index, int count, const std::string& format);

struct SegmentSet {
    std::string format;                // "mp4", "mkv" or "webm"
    std::vector<std::string> paths;    // segment 0 .. N-1
    // The soundtrack, as 48 kHz stereo 16-bit WAV files read one after another (a segment's
    // is segment-K-of-N.wav beside it); none: a silent video.
    std::vector<std::string> sound;
};
// The segments in `dir`: every segment-K-of-N.FORMAT for K in 0..N-1, of one N and one format,
// with their sounds if every segment has one. Other files are ignored; a missing segment or
// sound, or segments of different counts or formats, is an error that names them.
Expected<SegmentSet> find_segments(const std::string& dir);

// Joins the segments (in order), and their sound as AAC (.mp4, .mkv) or Opus (.webm), into `out`, whose target's extension must name their format,
// by copying their packets: no frame is decoded or encoded again. The segments must be of one
// codec, size, frame rate and encoder set-up, each starting with a keyframe, and all but the
// last of one length. Frames are renumbered from 0, so the result depends only on the
// segments' bytes. `out` (from OutputFile::create, made before any work so that an unwritable
// target fails first) is sealed, for the caller to commit.
Status join_segments(const SegmentSet& segments, OutputFile& out);

// A soundtrack alone: interleaved 16-bit PCM in a WAV file, through libavformat's wav muxer
// (bit-exact: no encoder tag), written under a temporary name until committed.
class WavWriter {
public:
    static Expected<WavWriter> open(const std::string& path, int sample_rate, int channels);
    ~WavWriter();
    WavWriter(WavWriter&&) noexcept;
    WavWriter& operator=(WavWriter&&) noexcept;

    Status write(std::span<const std::int16_t> samples);   // whole frames, interleaved
    Status seal();                                          // the header's sizes, then close
    OutputFile& file();                                     // after seal(): to commit

private:
    struct Impl;
    explicit WavWriter(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

// PNG stills for goldens and single frames: decoded/encoded with libavcodec's PNG codec.
// Reading trusts nothing about the file: the header is read first (a file that is no PNG, or
// whose pixels would outnumber the largest frame discreel renders, 7680x4320, is refused
// before anything else is read), then at most as many bytes as a PNG of that size can hold.
struct ImageSize {
    int width = 0;    // pixels
    int height = 0;   // pixels
    friend bool operator==(const ImageSize&, const ImageSize&) = default;
};
Expected<ImageSize> read_png_size(const std::string& path);
Expected<Image> read_png(const std::string& path);
Status write_png(const std::string& path, const ImageView& image);   // atomic: temp + rename
// The PNG written and sealed under a temporary name, for commit_together() with other files.
Expected<OutputFile> prepare_png(const std::string& path, const ImageView& image);
// 16-bit grey images (instance masks: one id per pixel), top row first.
struct Gray16View {
    int width = 0, height = 0;
    std::span<const std::uint16_t> values;   // width x height
};
struct Gray16Image {
    int width = 0, height = 0;
    std::vector<std::uint16_t> values;
};
// A 16-bit grey PNG written and sealed under a temporary name, for commit_together().
Expected<OutputFile> prepare_png_gray16(const std::string& path, const Gray16View& image);
Expected<Gray16Image> read_png_gray16(const std::string& path);
// The PNG bytes a still of `image` is written as, in memory (the studio's previews).
Expected<std::vector<std::uint8_t>> png_bytes(const ImageView& image);
// "data:image/png;base64,...": the image as a PNG an HTML page can carry inside itself.
Expected<std::string> png_data_uri(const ImageView& image);

}  // namespace discreel::encode
