#include "test_support.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

extern char** environ;

namespace discreel::testing {

TempDir::TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "discreel-test-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
}

TempDir::~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
}

std::string read_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream content;
    content << in.rdbuf();
    return content.str();
}

std::vector<std::string> directory_entries(const std::filesystem::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

void write_file(const std::filesystem::path& path, const std::string& content) {
    std::ofstream(path, std::ios::binary) << content;
}

CommandResult run_command(const std::vector<std::string>& argv) { return run_command(argv, {}); }

CommandResult run_command(const std::vector<std::string>& argv,
                          const std::map<std::string, std::string>& environment) {
    std::vector<std::string> variables;
    for (char** entry = environ; *entry != nullptr; ++entry) {
        const std::string variable(*entry);
        if (!environment.count(variable.substr(0, variable.find('=')))) variables.push_back(variable);
    }
    for (const auto& [name, value] : environment) variables.push_back(name + "=" + value);
    std::vector<char*> envp;
    for (std::string& v : variables) envp.push_back(v.data());
    envp.push_back(nullptr);
    TempDir capture;
    const std::string out_path = capture / "stdout";
    const std::string err_path = capture / "stderr";
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    pid_t pid = 0;
    CommandResult result;
    if (posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), envp.data()) == 0) {
        int status = 0;
        ::waitpid(pid, &status, 0);
        result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    posix_spawn_file_actions_destroy(&actions);
    result.out = read_file(out_path);
    result.err = read_file(err_path);
    return result;
}

std::map<std::string, std::string> probe_video(const std::string& path) {
    const CommandResult probe = run_command(
        {"ffprobe", "-v", "error", "-select_streams", "v:0", "-count_frames", "-show_entries",
         "stream=codec_name,profile,pix_fmt,width,height,r_frame_rate,duration,nb_read_frames,"
         "color_space,color_transfer,color_primaries,color_range",
         "-of", "default=noprint_wrappers=1", path});
    std::map<std::string, std::string> fields;
    if (probe.exit_code != 0) return fields;
    std::istringstream lines(probe.out);
    for (std::string line; std::getline(lines, line);) {
        const auto eq = line.find('=');
        if (eq != std::string::npos) fields[line.substr(0, eq)] = line.substr(eq + 1);
    }
    return fields;
}

std::vector<std::uint8_t> decode_first_frame_rgb24(const std::string& path) {
    const CommandResult decode = run_command({"ffmpeg", "-v", "error", "-i", path, "-frames:v", "1",
                                              "-f", "rawvideo", "-pix_fmt", "rgb24", "-"});
    if (decode.exit_code != 0) return {};
    return {decode.out.begin(), decode.out.end()};
}

std::vector<std::uint8_t> decode_frames_rgb24(const std::string& path) {
    const CommandResult decode = run_command(
        // passthrough: every decoded frame once, none duplicated or dropped to fit a frame rate
        // (GIF delays are whole centiseconds, so its timestamps are not evenly spaced).
        {"ffmpeg", "-v", "error", "-i", path, "-fps_mode", "passthrough", "-f", "rawvideo",
         "-pix_fmt", "rgb24", "-"});
    if (decode.exit_code != 0) return {};
    return {decode.out.begin(), decode.out.end()};
}

std::vector<std::string> mp4_top_level_boxes(const std::string& path) {
    const std::string bytes = read_file(path);
    const auto read_be = [&](std::uint64_t at, int count) {
        std::uint64_t value = 0;
        for (int i = 0; i < count; ++i) value = (value << 8) | static_cast<std::uint8_t>(bytes[at + i]);
        return value;
    };
    std::vector<std::string> types;
    std::uint64_t offset = 0;
    while (offset + 8 <= bytes.size()) {
        std::uint64_t size = read_be(offset, 4);
        types.push_back(bytes.substr(offset + 4, 4));
        if (size == 1 && offset + 16 <= bytes.size()) {   // 64-bit "largesize" follows the type
            size = read_be(offset + 8, 8);
        } else if (size == 0) {                             // the box runs to the end of the file
            size = bytes.size() - offset;
        }
        if (size < 8) {
            types.push_back("<malformed>");
            break;
        }
        offset += size;
    }
    return types;
}

}  // namespace discreel::testing
