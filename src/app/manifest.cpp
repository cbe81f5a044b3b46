#include "manifest.hpp"

#include "discreel/parse_number.hpp"

namespace discreel::app {

Expected<std::vector<std::string>> split_words(std::string_view line) {
    std::vector<std::string> words;
    std::string word;
    bool in_word = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (c == ' ' || c == '\t' || c == '\r') {
            if (in_word) words.push_back(std::move(word));
            word.clear();
            in_word = false;
            continue;
        }
        in_word = true;
        if (c == '\'') {
            const auto end = line.find('\'', i + 1);
            if (end == std::string_view::npos) return Error{"unterminated ' quote"};
            word.append(line.substr(i + 1, end - i - 1));
            i = end;
        } else if (c == '"') {
            for (++i;; ++i) {
                if (i >= line.size()) return Error{"unterminated \" quote"};
                if (line[i] == '"') break;
                if (line[i] == '\\' && i + 1 < line.size() &&
                    (line[i + 1] == '"' || line[i + 1] == '\\')) {
                    ++i;
                }
                word += line[i];
            }
        } else if (c == '\\') {
            if (i + 1 >= line.size()) return Error{"a backslash ends the line"};
            word += line[++i];
        } else {
            word += c;
        }
    }
    if (in_word) words.push_back(std::move(word));
    return words;
}

Expected<ManifestLine> pick_render(std::string_view text, std::size_t index,
                                   const std::string& manifest) {
    std::size_t renders = 0;
    int number = 0;
    for (std::size_t start = 0; start < text.size();) {
        auto end = text.find('\n', start);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view line = text.substr(start, end - start);
        start = end + 1;
        ++number;
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string_view::npos || line[first] == '#') continue;
        if (renders++ != index) continue;
        auto words = split_words(line);
        if (!words) {
            return Error{manifest + ":" + std::to_string(number) + ": " + words.error().message};
        }
        return ManifestLine{number, std::move(*words)};
    }
    std::string message = "index " + std::to_string(index) + " is past the end of " + manifest +
                          ", which has " + std::to_string(renders);
    if (renders == 0) return Error{message + " renders"};
    if (renders == 1) return Error{message + " render (index 0)"};
    return Error{message + " renders (indexes 0 to " + std::to_string(renders - 1) + ")"};
}

std::size_t count_renders(std::string_view text) {
    std::size_t renders = 0;
    for (std::size_t start = 0; start < text.size();) {
        auto end = text.find('\n', start);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view line = text.substr(start, end - start);
        start = end + 1;
        const auto first = line.find_first_not_of(" \t\r");
        if (first != std::string_view::npos && line[first] != '#') ++renders;
    }
    return renders;
}

Expected<IndexRange> parse_index_range(std::string_view text) {
    const auto dash = text.find('-');
    const auto first = parse_whole<std::size_t>(text.substr(0, dash));
    const auto last = dash == std::string_view::npos
                          ? first
                          : parse_whole<std::size_t>(text.substr(dash + 1));
    if (!first || !last || *last < *first) {
        return Error{"expected an index I or a range A-B of indexes (A <= B, from 0), got '" +
                     std::string(text) + "'"};
    }
    return IndexRange{*first, *last};
}

Expected<IndexRange> batch_index(std::optional<IndexRange> flag,
                                 const char* (*getenv)(const char*)) {
    if (flag) return *flag;
    for (const char* name : {"SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX"}) {
        const char* value = getenv(name);
        if (value == nullptr || *value == '\0') continue;
        const std::string_view text = value;
        const auto index = parse_whole<std::size_t>(text);
        if (!index) {
            return Error{std::string(name) + " is '" + value + "', not an index (0, 1, 2, ...)"};
        }
        return IndexRange{*index, *index};
    }
    return Error{"batch needs the render's index: --index I (or A-B, or --all), or SLURM_ARRAY_TASK_ID (a Slurm "
                 "job array) or JOB_COMPLETION_INDEX (a Kubernetes indexed Job) in the "
                 "environment"};
}

}  // namespace discreel::app
