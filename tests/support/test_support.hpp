#pragma once
// Test helpers: a temporary directory that cleans up after itself, running a shell command and
// capturing its output and exit code, reading files, and asking ffprobe about a media file.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace discreel::testing {

class TempDir {
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::filesystem::path& path() const { return path_; }
    std::string operator/(const std::string& name) const { return (path_ / name).string(); }

private:
    std::filesystem::path path_;
};

struct CommandResult {
    int exit_code = -1;
    std::string out;   // stdout
    std::string err;   // stderr
};

// Runs `argv` (no shell interpretation of the arguments) with stdin from /dev/null.
CommandResult run_command(const std::vector<std::string>& argv);
// The same, with `environment` set on top of this process's environment (e.g. LP_NUM_THREADS).
CommandResult run_command(const std::vector<std::string>& argv,
                          const std::map<std::string, std::string>& environment);

std::string read_file(const std::filesystem::path& path);

// The names in `dir`, sorted: what a test expects to find (or not) after a run.
std::vector<std::string> directory_entries(const std::filesystem::path& dir);
void write_file(const std::filesystem::path& path, const std::string& content);

// ffprobe's view of the first video stream: codec_name, profile, pix_fmt, width, height,
// r_frame_rate, duration, nb_read_frames (frames counted by decoding the whole stream, so it is
// what a player gets), color_space, color_transfer, color_primaries, color_range. ffprobe is an
// independent reader: tests check what players see, not what our code believes it wrote.
// Empty when ffprobe fails.
std::map<std::string, std::string> probe_video(const std::string& path);

// The first frame as decoded by the ffmpeg CLI, packed RGB24. ffmpeg honours the stream's colour
// tags when converting, as HD players do. Empty when ffmpeg fails.
std::vector<std::uint8_t> decode_first_frame_rgb24(const std::string& path);

// Every frame as decoded by the ffmpeg CLI, packed RGB24, one after the other (frame i starts
// at i * 3 * width * height). Empty when ffmpeg fails.
std::vector<std::uint8_t> decode_frames_rgb24(const std::string& path);

// Types of the top-level boxes of an MP4/MOV file, in file order ("ftyp", "moov", "mdat", ...);
// "<malformed>" ends the list where a box size makes no sense.
std::vector<std::string> mp4_top_level_boxes(const std::string& path);

}  // namespace discreel::testing
