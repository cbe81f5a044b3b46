#pragma once
// An HTML report of a golden run, as Playwright's and pytest-mpl's: one self-contained page
// (images inlined as data: URIs, no scripts, no external files) listing every frame that did
// not match with its golden, actual and difference images side by side and the numbers.
#include <string>
#include <vector>

namespace discreel::golden {

struct ReportFrame {
    std::string scene;        // scene name
    std::string frame;        // "frame_<n>"
    bool passed = true;
    bool written = false;     // --update wrote this golden
    std::string message;      // the line the command printed for it
    // data: URIs of PNGs; empty where there is none (no golden yet, or sizes differ).
    std::string golden_image, actual_image, diff_image;
};

// The page for a run over `scene_count` scenes; `title` heads it.
std::string html_report(const std::string& title, std::size_t scene_count,
                        const std::vector<ReportFrame>& frames);

}  // namespace discreel::golden
