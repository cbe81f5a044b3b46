#include "test_support.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

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

void write_file(const std::filesystem::path& path, const std::string& content) {
    std::ofstream(path, std::ios::binary) << content;
}

CommandResult run_command(const std::vector<std::string>& argv) {
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
    if (posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ) == 0) {
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
         "stream=codec_name,pix_fmt,width,height,nb_read_frames,color_space,color_transfer,"
         "color_primaries,color_range:format=duration,format_name",
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

std::vector<std::string> mp4_top_level_boxes(const std::string& path) {
    const std::string data = read_file(path);
    std::vector<std::string> boxes;
    std::size_t at = 0;
    while (at + 8 <= data.size()) {
        const auto byte = [&](std::size_t i) { return static_cast<std::uint8_t>(data[at + i]); };
        std::uint64_t size = (std::uint64_t{byte(0)} << 24) | (byte(1) << 16) | (byte(2) << 8) | byte(3);
        boxes.push_back(data.substr(at + 4, 4));
        if (size == 1 && at + 16 <= data.size()) {   // 64-bit size follows the type
            size = 0;
            for (int i = 8; i < 16; ++i) size = (size << 8) | byte(i);
        }
        if (size < 8) break;
        at += size;
    }
    return boxes;
}

}  // namespace discreel::testing
