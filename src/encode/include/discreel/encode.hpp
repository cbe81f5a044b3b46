#pragma once
// Frames in, files out (libavformat/libavcodec/libswscale behind this header). A Sink writes to
// a temporary file beside the target and renames it onto the target only in finish(): a sink
// destroyed without a successful finish() deletes its temporary file, so the target path holds
// either the complete new output or whatever was there before.
#include <memory>
#include <string>

#include "discreel/expected.hpp"
#include "discreel/image.hpp"

namespace discreel::encode {

struct SinkDef {
    std::string path;              // output file; the extension picks the format (.mp4, .png)
    int width = 1280;              // pixels, even for video
    int height = 720;              // pixels, even for video
    int fps = 60;                  // frames per second
    int crf = 20;                  // H.264 constant rate factor, 0..51 (lower is better)
    std::string preset = "veryfast";  // x264 preset
    int threads = 2;               // encoder threads; pinned, because x264's bytes depend on it
};

class Sink {
public:
    virtual ~Sink() = default;
    virtual Status write(const ImageView& frame) = 0;   // frames in presentation order
    virtual Status finish() = 0;                        // flush, close, rename into place
};

// Opens the sink that the extension of def.path names (case-insensitive): .mp4 is H.264 in
// MP4 (yuv420p, BT.709 limited range, index first); .png is a still that takes exactly one
// frame. Fails for unknown extensions, odd sizes for video, missing or unwritable directories,
// bad encoder settings and encoders that cannot be opened. Errors name the path.
Expected<std::unique_ptr<Sink>> open_sink(const SinkDef& def);

// PNG stills for goldens and single frames: decoded/encoded with libavcodec's PNG codec.
Expected<Image> read_png(const std::string& path);
Status write_png(const std::string& path, const ImageView& image);   // atomic: temp + rename

}  // namespace discreel::encode
