#pragma once
// Which paths name the same file: by device and inode where the file exists, otherwise by the
// path with every symbolic link followed. A command that would write one of its inputs, or
// write two of its outputs to one file, is refused before it starts.
#include <optional>
#include <string>
#include <vector>

namespace discreel {

// `path` with its symbolic links followed, the last component included even when the link
// dangles (what a write through the link creates); made absolute. Loops of links end after 40.
std::string real_path(const std::string& path);

bool same_file(const std::string& a, const std::string& b);

struct NamedPath {
    std::string role;   // "the scene", "--trace", "-o"
    std::string path;
};

// The first clash among `outputs` and between an output and one of `inputs`, in words
// ("--trace 'x.yaml' is the scene file 'x.yaml'"), or nullopt when all are distinct.
std::optional<std::string> find_clash(const std::vector<NamedPath>& inputs,
                                      const std::vector<NamedPath>& outputs);

}  // namespace discreel
