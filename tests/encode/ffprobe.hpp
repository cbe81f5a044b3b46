#pragma once
// Runs the ffmpeg / ffprobe command-line tools on files the sinks wrote: an independent reader,
// so the tests check what players see rather than what our own code believes it wrote.
#include <cstdint>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace discreel::encode::test {

inline std::string command_output(const std::string& command) {
    std::string output;
    FILE* pipe = popen(command.c_str(), "r");
    if (pipe == nullptr) {
        return output;
    }
    char buffer[4096];
    std::size_t count = 0;
    while ((count = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) {
        output.append(buffer, count);
    }
    pclose(pipe);
    return output;
}

// key -> value for the first video stream, from ffprobe's flat "key=value" output. Counting
// frames decodes the whole stream, so nb_read_frames is what a player actually gets.
inline std::map<std::string, std::string> probe_video_stream(const std::string& path) {
    const std::string command =
        "ffprobe -v error -select_streams v:0 -count_frames -show_entries "
        "stream=codec_name,profile,pix_fmt,width,height,nb_read_frames,duration,r_frame_rate,"
        "color_space,color_primaries,color_transfer,color_range "
        "-of default=noprint_wrappers=1 '" + path + "'";
    std::map<std::string, std::string> fields;
    std::istringstream lines(command_output(command));
    for (std::string line; std::getline(lines, line);) {
        const auto equals = line.find('=');
        if (equals != std::string::npos) {
            fields[line.substr(0, equals)] = line.substr(equals + 1);
        }
    }
    return fields;
}

// The first frame decoded by the ffmpeg CLI as packed RGB24. ffmpeg honours the stream's
// colour tags when converting, as HD players do.
inline std::vector<std::uint8_t> decode_first_frame_rgb24(const std::string& path) {
    const std::string output = command_output("ffmpeg -v error -i '" + path +
                                              "' -frames:v 1 -f rawvideo -pix_fmt rgb24 -");
    return {output.begin(), output.end()};
}

}  // namespace discreel::encode::test
