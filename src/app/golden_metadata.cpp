#include "golden_metadata.hpp"

#include "discreel/read_file.hpp"
#include <sstream>

#include "discreel/printable.hpp"

namespace discreel::golden {

std::optional<Metadata> read_metadata(const std::filesystem::path& scene_dir) {
    constexpr std::uintmax_t max_bytes = 1 << 16;   // a few short lines; more is not ours
    const auto text = read_file_bounded((scene_dir / metadata_file_name).string(), max_bytes);
    if (!text || text->too_large) return std::nullopt;
    std::istringstream file(text->bytes);
    Metadata m;
    std::string line;
    while (std::getline(file, line)) {
        const auto colon = line.find(": ");
        if (line.empty() || line[0] == '#' || colon == std::string::npos) continue;
        const std::string key = line.substr(0, colon);
        const std::string value = line.substr(colon + 2);
        if (key == "discreel") m.discreel_version = value;
        if (key == "renderer") m.renderer = value;
        if (key == "size") {
            char x = 0;
            std::istringstream(value) >> m.width >> x >> m.height;
        }
    }
    if (m.renderer.empty()) return std::nullopt;
    return m;
}

Expected<AtomicTextFile> prepare_metadata(const std::filesystem::path& scene_dir,
                                               const Metadata& m) {
    auto file = AtomicTextFile::create((scene_dir / metadata_file_name).string());
    if (!file) return file.error();
    file->write("# Written by `discreel golden --update`: what the frame_<n>.png beside it were "
                "rendered with.\n");
    file->write("discreel: " + m.discreel_version + "\n");
    file->write("renderer: " + m.renderer + "\n");
    file->write("size: " + std::to_string(m.width) + "x" + std::to_string(m.height) + "\n");
    if (Status sealed = file->seal(); !sealed) return sealed.error();
    return file;
}

}  // namespace discreel::golden
