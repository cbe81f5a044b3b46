// Inputs too big for the fuzzer (-max_len) to produce: the size limit is enforced before any
// byte is parsed, for files and for text alike.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "discreel/scene.hpp"

namespace discreel::scene {
namespace {

namespace fs = std::filesystem;

constexpr std::uintmax_t hundred_mb = 100u << 20;

std::string only_message(const LoadResult& result) {
    if (result.diagnostics.size() != 1) return "expected one diagnostic, got " +
                                               std::to_string(result.diagnostics.size());
    return result.diagnostics.front().to_string();
}

TEST(HugeInput, AHundredMegabyteFileIsRejectedBeforeReading) {
    const fs::path path = fs::path(DISCREEL_BINARY_DIR) / "huge_input_test.yaml";
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out << "version: 1\n";
    }
    // Sparse: the test neither writes nor reads 100 MB.
    fs::resize_file(path, hundred_mb);
    const LoadResult result = load_scene_file(path);
    fs::remove(path);
    EXPECT_EQ(only_message(result),
              path.string() + ": the file is too large (104857600 bytes); the limit is "
                              "67108864 bytes (raise it with --max-scene-bytes)");
}

TEST(HugeInput, AHundredMegabytesOfTextAreRejectedBeforeParsing) {
    // A flow sequence that never closes: parsing it would take minutes and gigabytes.
    std::string text = "version: 1\nwalls: [";
    text.resize(hundred_mb, '[');
    EXPECT_EQ(only_message(load_scene_text(text, "huge.yaml")),
              "huge.yaml: the file is too large (104857600 bytes); the limit is 67108864 "
              "bytes (raise it with --max-scene-bytes)");
}

TEST(HugeInput, TextOneByteOverTheLimitIsRejected) {
    std::string text = "version: 1\n#";
    text.resize(Limits{}.file_bytes + 1, 'x');
    EXPECT_EQ(only_message(load_scene_text(text, "over.yaml")),
              "over.yaml: the file is too large (67108865 bytes); the limit is 67108864 bytes "
              "(raise it with --max-scene-bytes)");
}

}  // namespace
}  // namespace discreel::scene
