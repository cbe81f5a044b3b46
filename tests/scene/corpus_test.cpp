// The bad-input corpus: every tests/data/bad/<name>.yaml must produce exactly the diagnostics
// in <name>.expected, one per line, as Diagnostic::to_string() prints them with the file shown
// as "<name>.yaml". The warnings corpus, tests/data/warn/, the same for scenes that load with
// warnings. Adding a case needs no code: drop in the two files.
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

// Each scene of tests/data/<name>/ (sorted), loaded, with the text of its .expected file.
struct Case {
    fs::path scene;
    LoadResult result;
    std::string expected;
};

std::vector<Case> corpus(const std::string& name) {
    const fs::path dir = fs::path(DISCREEL_SOURCE_DIR) / "tests" / "data" / name;
    std::vector<fs::path> scenes;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.path().extension() == ".yaml") scenes.push_back(entry.path());
    std::sort(scenes.begin(), scenes.end());
    std::vector<Case> cases;
    for (const fs::path& scene : scenes) {
        fs::path expected = scene;
        expected.replace_extension(".expected");
        EXPECT_TRUE(fs::exists(expected)) << "missing " << expected;
        cases.push_back({scene, load_scene_text(read_text(scene), scene.filename().string()),
                         read_text(expected)});
    }
    return cases;
}

std::string lines_of(const std::vector<Diagnostic>& diagnostics) {
    std::string text;
    for (const Diagnostic& d : diagnostics) text += d.to_string() + "\n";
    return text;
}

TEST(BadInputCorpus, EveryFileGivesExactlyItsExpectedDiagnostics) {
    const std::vector<Case> cases = corpus("bad");
    // Guards against a wrong directory silently passing with nothing to compare.
    ASSERT_GE(cases.size(), 20u);
    for (const Case& c : cases) {
        SCOPED_TRACE(c.scene.filename().string());
        EXPECT_FALSE(c.result.ok()) << "a bad-input file that loads is in the wrong corpus";
        EXPECT_EQ(lines_of(c.result.diagnostics), c.expected);
    }
}

TEST(WarningCorpus, EveryFileLoadsWithExactlyItsExpectedWarnings) {
    const std::vector<Case> cases = corpus("warn");
    ASSERT_GE(cases.size(), 4u);
    for (const Case& c : cases) {
        SCOPED_TRACE(c.scene.filename().string());
        EXPECT_EQ(lines_of(c.result.diagnostics), "") << "a file that fails is in the wrong corpus";
        EXPECT_NE(lines_of(c.result.warnings), "")
            << "a file that loads without warnings is in the wrong corpus";
        EXPECT_EQ(lines_of(c.result.warnings), c.expected);
    }
}

}  // namespace
}  // namespace discreel::scene
