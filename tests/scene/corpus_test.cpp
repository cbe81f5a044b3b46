// The bad-input corpus: every tests/data/bad/<name>.yaml must produce exactly the diagnostics
// in <name>.expected, one per line, as Diagnostic::to_string() prints them with the file shown
// as "<name>.yaml". Adding a case needs no code: drop in the two files.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "discreel/scene.hpp"

namespace discreel::scene {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

TEST(BadInputCorpus, EveryFileGivesExactlyItsExpectedDiagnostics) {
    const fs::path dir = fs::path(DISCREEL_SOURCE_DIR) / "tests" / "data" / "bad";
    std::vector<fs::path> scenes;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.path().extension() == ".yaml") scenes.push_back(entry.path());
    std::sort(scenes.begin(), scenes.end());
    // Guards against a wrong directory silently passing with nothing to compare.
    ASSERT_GE(scenes.size(), 20u) << dir;

    for (const fs::path& scene : scenes) {
        SCOPED_TRACE(scene.filename().string());
        fs::path expected_path = scene;
        expected_path.replace_extension(".expected");
        ASSERT_TRUE(fs::exists(expected_path)) << "missing " << expected_path;
        const LoadResult result =
            load_scene_text(read_text(scene), scene.filename().string());
        std::string actual;
        for (const Diagnostic& d : result.diagnostics) actual += d.to_string() + "\n";
        EXPECT_FALSE(result.ok()) << "a bad-input file that loads is in the wrong corpus";
        EXPECT_EQ(actual, read_text(expected_path));
    }
}

}  // namespace
}  // namespace discreel::scene
