#pragma once
// What a scene's golden images were made with, kept beside them in D/<scene>/golden.txt as
// `key: value` lines, so that a mismatch caused by another renderer (a different Mesa or LLVM)
// is told apart from a regression.
#include <filesystem>
#include <optional>
#include <string>

#include "discreel/atomic_text_file.hpp"
#include "discreel/expected.hpp"

namespace discreel::golden {

struct Metadata {
    std::string discreel_version;   // e.g. "0.1.0"
    std::string renderer;           // render::Renderer::renderer_info(): GL_RENDERER; GL_VERSION
    int width = 0, height = 0;      // pixels, of every frame_<n>.png
};

inline constexpr const char* metadata_file_name = "golden.txt";

// None when the file does not exist, is not a small text file, or holds no renderer line
// (goldens made by hand).
std::optional<Metadata> read_metadata(const std::filesystem::path& scene_dir);
// The file written under a temporary name, to be committed with the goldens it describes.
Expected<AtomicTextFile> prepare_metadata(const std::filesystem::path& scene_dir,
                                               const Metadata& metadata);

}  // namespace discreel::golden
