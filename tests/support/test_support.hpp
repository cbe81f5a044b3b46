#pragma once
// Test helpers: a temporary directory that cleans up after itself, running a shell command and
// capturing its output and exit code, reading files, and asking ffprobe about a media file.
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

std::string read_file(const std::filesystem::path& path);
void write_file(const std::filesystem::path& path, const std::string& content);

// ffprobe's view of the first video stream and the container: keys such as codec_name, pix_fmt,
// width, height, nb_read_frames, color_space, color_transfer, color_primaries, color_range,
// duration (the container's). Empty when ffprobe fails.
std::map<std::string, std::string> probe_video(const std::string& path);

// Names of the top-level boxes of an MP4/MOV file, in file order ("ftyp", "moov", "mdat", ...).
std::vector<std::string> mp4_top_level_boxes(const std::string& path);

}  // namespace discreel::testing
