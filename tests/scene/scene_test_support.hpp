#pragma once
// Helpers shared by the scene tests: load YAML text and look at the outcome as plain strings.
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "discreel/scene.hpp"

namespace discreel::scene::testing {

// Every diagnostic as the CLI prints it, for the file name "s.yaml".
inline std::vector<std::string> problems(std::string_view yaml) {
    std::vector<std::string> lines;
    for (const Diagnostic& d : load_scene_text(yaml, "s.yaml").diagnostics)
        lines.push_back(d.to_string());
    return lines;
}

// The warnings of a file that must load, as printed; a failure to load shows the diagnostics.
inline std::vector<std::string> warnings(std::string_view yaml) {
    const LoadResult result = load_scene_text(yaml, "s.yaml");
    std::string shown;
    for (const Diagnostic& d : result.diagnostics) shown += d.to_string() + "\n";
    EXPECT_TRUE(result.ok()) << shown;
    std::vector<std::string> lines;
    for (const Diagnostic& d : result.warnings) lines.push_back(d.to_string());
    return lines;
}

// The scene of a file that must load cleanly; a failure shows the diagnostics.
inline Scene load_ok(std::string_view yaml) {
    LoadResult result = load_scene_text(yaml, "s.yaml");
    std::string shown;
    for (const Diagnostic& d : result.diagnostics) shown += d.to_string() + "\n";
    EXPECT_TRUE(result.ok()) << shown;
    return std::move(result.scene);
}

}  // namespace discreel::scene::testing
