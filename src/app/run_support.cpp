#include "run_support.hpp"

#include <filesystem>
#include <fstream>

#include "discreel/printable.hpp"
#include <string>

namespace discreel::app {

std::optional<std::int64_t> peak_resident_bytes() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line)) {
        if (line.rfind("VmHWM:", 0) == 0) return std::stoll(line.substr(6)) * 1024;   // kB
    }
    return std::nullopt;
}

void report_error(std::ostream& err, std::string_view message) {
    err << "discreel: " << printable(message) << '\n';
}

bool report_diagnostics(const scene::LoadResult& loaded, std::ostream& err, bool warnings) {
    for (const scene::Diagnostic& d : loaded.diagnostics) err << d.to_string() << '\n';
    if (warnings) {
        for (const scene::Diagnostic& d : loaded.warnings) err << d.to_string() << '\n';
    }
    return loaded.ok();
}

bool check_distinct_files(const std::vector<NamedPath>& inputs,
                          const std::vector<NamedPath>& outputs, std::ostream& err) {
    const auto clash = find_clash(inputs, outputs);
    if (clash) report_error(err, *clash);
    return !clash;
}

bool make_output_directories(const std::vector<NamedPath>& outputs, std::ostream& err) {
    for (const NamedPath& output : outputs) {
        const std::filesystem::path parent = std::filesystem::path(output.path).parent_path();
        std::error_code error;
        // Something else in the directory's place is the writer's to report, in its words.
        if (parent.empty() || std::filesystem::exists(parent, error)) continue;
        std::filesystem::create_directories(parent, error);
        if (error && !std::filesystem::is_directory(parent)) {
            std::string message = "cannot make the directory '";
            message.append(printable(parent.string()))
                .append("' for ")
                .append(output.role)
                .append(": ")
                .append(error.message());
            report_error(err, message);
            return false;
        }
    }
    return true;
}

void add_output_paths(const OutputFiles& files, std::vector<NamedPath>& outputs) {
    if (files.trace) outputs.push_back({"--trace", *files.trace});
    if (files.events) outputs.push_back({"--events", *files.events});
    if (files.joints) outputs.push_back({"--joints", *files.joints});
    if (files.shapes) outputs.push_back({"--shapes", *files.shapes});
    if (files.camera) outputs.push_back({"--camera", *files.camera});
    if (files.boxes) outputs.push_back({"--boxes", *files.boxes});
    // The masks' directory, made like the others' (its first file stands for it).
    if (files.masks) outputs.push_back({"--masks", *files.masks + "/mask_00000.png"});
}

bool standard_output_ok(std::ostream& out, std::ostream& err) {
    out.flush();
    if (out) return true;
    report_error(err, "cannot write to standard output");
    return false;
}

}  // namespace discreel::app
