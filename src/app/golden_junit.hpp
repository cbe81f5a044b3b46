#pragma once
// A JUnit XML report of a golden run, the format CI systems (GitLab, Jenkins, GitHub actions
// with a reporter) display as a list of passed and failed test cases.
#include <string>
#include <vector>

namespace discreel::golden {

struct CaseResult {
    std::string scene;     // scene name; becomes the test case's classname
    std::string name;      // "frame_<n>"
    bool passed = true;
    std::string message;   // why it failed: one line
    std::string details;   // more lines for the failure's body (files written, renderer); optional
    double seconds = 0;    // simulating up to the frame, drawing and checking it
};

// One <testsuite> named `suite` holding one <testcase> per result, in order.
std::string junit_xml(const std::string& suite, const std::vector<CaseResult>& results);

// `text` with the five XML special characters replaced by entities, and control characters
// that XML 1.0 cannot carry replaced by U+FFFD; safe inside attributes and element text.
std::string xml_escape(const std::string& text);

}  // namespace discreel::golden
