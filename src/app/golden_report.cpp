#include "golden_report.hpp"

#include <algorithm>

#include "golden_junit.hpp"

namespace discreel::golden {
namespace {

// Checkerboard behind the images, so transparent pixels read as transparent.
constexpr const char* style = R"(<style>
body { font: 14px/1.4 system-ui, sans-serif; margin: 2em; color: #1b1f24; }
h1 { font-size: 20px; } h2 { font-size: 16px; margin: 1.5em 0 0.3em; }
.failed { color: #b42318; } .passed { color: #067647; }
.frame { border-top: 1px solid #d0d5dd; padding-bottom: 1em; }
.images { display: flex; gap: 12px; flex-wrap: wrap; }
figure { margin: 0; } figcaption { font-size: 12px; color: #475467; }
img { max-width: 420px; border: 1px solid #d0d5dd; image-rendering: pixelated;
      background: repeating-conic-gradient(#eee 0 25%, #fff 0 50%) 0 0 / 16px 16px; }
code { background: #f2f4f7; padding: 0 3px; }
.wipe { position: relative; display: inline-block; line-height: 0; }
.wipe img { display: block; }
.wipe .over { position: absolute; left: 0; top: 0; clip-path: inset(0 0 0 var(--at, 50%)); }
.wipe .diff { position: absolute; left: 0; top: 0; opacity: var(--diff, 0); }
.controls { font-size: 12px; color: #475467; display: flex; gap: 16px; margin: 4px 0; }
details { margin-top: 1.5em; } summary { cursor: pointer; }
</style>
)";

// The wipe: the golden under the actual frame, the actual clipped from the left edge to the
// slider's place, and the difference laid over both as the second slider says. No script but
// the sliders' own attributes, so the page stays one self-contained file.
void wipe(std::string& html, const ReportFrame& f) {
    if (f.golden_image.empty() || f.actual_image.empty() || f.diff_image.empty()) return;
    html += "<figure><div class=\"wipe\"><img alt=\"golden\" src=\"" + f.golden_image +
            "\"><img class=\"over\" alt=\"actual\" src=\"" + f.actual_image +
            "\"><img class=\"diff\" alt=\"difference\" src=\"" + f.diff_image +
            "\"></div>\n<div class=\"controls\"><label>golden | actual <input type=\"range\" "
            "min=\"0\" max=\"100\" value=\"50\" oninput=\"this.closest('figure')"
            ".querySelector('.wipe').style.setProperty('--at', this.value + '%')\"></label>"
            "<label>difference <input type=\"range\" min=\"0\" max=\"100\" value=\"0\" "
            "oninput=\"this.closest('figure').querySelector('.wipe').style.setProperty('--diff',"
            " this.value / 100)\"></label></div><figcaption>wipe: golden left of the line, "
            "actual right of it</figcaption></figure>\n";
}

std::string count(std::size_t n, const std::string& noun) {
    return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

void figure(std::string& html, const std::string& caption, const std::string& uri) {
    if (uri.empty()) return;
    html += "<figure><img alt=\"" + caption + "\" src=\"" + uri + "\"><figcaption>" + caption +
            "</figcaption></figure>\n";
}

}  // namespace

std::string html_report(const std::string& title, std::size_t scene_count,
                        const std::vector<ReportFrame>& frames) {
    const auto failed = static_cast<std::size_t>(std::count_if(
        frames.begin(), frames.end(), [](const ReportFrame& f) { return !f.passed; }));
    const auto written = static_cast<std::size_t>(std::count_if(
        frames.begin(), frames.end(), [](const ReportFrame& f) { return f.written; }));
    std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                       "<title>" + xml_escape(title) + "</title>\n" + style + "</head>\n<body>\n";
    html += "<h1>" + xml_escape(title) + "</h1>\n<p>" + count(frames.size(), "frame") + " of " +
            count(scene_count, "scene") + ": <span class=\"passed\">" +
            std::to_string(frames.size() - failed - written) + " passed</span>, <span class=\"" +
            (failed > 0 ? "failed" : "passed") + "\">" + std::to_string(failed) +
            " failed</span>";
    if (written > 0) html += ", " + std::to_string(written) + " written";
    html += ".</p>\n";
    for (const ReportFrame& f : frames) {
        if (f.passed) continue;
        html += "<div class=\"frame\">\n<h2 class=\"failed\">" + xml_escape(f.scene) + " " +
                xml_escape(f.frame) + "</h2>\n<p>" + xml_escape(f.message) + "</p>\n";
        html += "<div class=\"images\">\n";
        figure(html, "golden", f.golden_image);
        figure(html, "actual", f.actual_image);
        figure(html, "difference (red: differs, yellow: anti-aliasing)", f.diff_image);
        wipe(html, f);
        html += "</div>\n</div>\n";
    }
    if (failed == 0) html += "<p class=\"passed\">Every frame matched its golden.</p>\n";
    const std::size_t passed = frames.size() - failed;
    if (passed > 0) {
        html += "<details><summary class=\"passed\">" + count(passed, "frame") +
                " passed or written</summary>\n<ul>\n";
        for (const ReportFrame& f : frames) {
            if (!f.passed) continue;
            html += "<li>" + xml_escape(f.scene) + " " + xml_escape(f.frame) + ": " +
                    xml_escape(f.message) + "</li>\n";
        }
        html += "</ul>\n</details>\n";
    }
    html += "</body>\n</html>\n";
    return html;
}

}  // namespace discreel::golden
