#include "golden_junit.hpp"

#include <algorithm>
#include <cstdio>
#include <numeric>

namespace discreel::golden {

std::string xml_escape(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&apos;"; break;
            case '\t':
            case '\n':
            case '\r': out += c; break;
            default:
                if (static_cast<unsigned char>(c) < 0x20) {
                    out += "\xEF\xBF\xBD";
                } else {
                    out += c;
                }
        }
    }
    return out;
}

namespace {

// JUnit's `time`: seconds with millisecond digits.
std::string time_attribute(double seconds) {
    char text[32];
    std::snprintf(text, sizeof text, " time=\"%.3f\"", seconds);
    return text;
}

}  // namespace

std::string junit_xml(const std::string& suite, const std::vector<CaseResult>& results) {
    const auto failures =
        std::count_if(results.begin(), results.end(), [](const CaseResult& r) { return !r.passed; });
    const double seconds = std::accumulate(
        results.begin(), results.end(), 0.0,
        [](double sum, const CaseResult& r) { return sum + r.seconds; });
    const std::string counts = " tests=\"" + std::to_string(results.size()) + "\" failures=\"" +
                               std::to_string(failures) + "\" errors=\"0\"" +
                               time_attribute(seconds);
    std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    xml += "<testsuites name=\"" + xml_escape(suite) + "\"" + counts + ">\n";
    xml += "  <testsuite name=\"" + xml_escape(suite) + "\"" + counts + ">\n";
    for (const CaseResult& r : results) {
        xml += "    <testcase classname=\"" + xml_escape(r.scene) + "\" name=\"" +
               xml_escape(r.name) + "\"" + time_attribute(r.seconds);
        if (r.passed) {
            xml += "/>\n";
            continue;
        }
        xml += ">\n      <failure message=\"" + xml_escape(r.message) + "\" type=\"golden mismatch\">" +
               xml_escape(r.details.empty() ? r.message : r.details) + "</failure>\n";
        xml += "    </testcase>\n";
    }
    xml += "  </testsuite>\n</testsuites>\n";
    return xml;
}

}  // namespace discreel::golden
