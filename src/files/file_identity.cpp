#include "discreel/file_identity.hpp"

#include <sys/stat.h>

#include <filesystem>
#include <system_error>

#include "discreel/printable.hpp"

namespace discreel {
namespace {

namespace fs = std::filesystem;

constexpr int max_link_hops = 40;   // as the kernel's own limit: a loop ends here

}  // namespace

std::string real_path(const std::string& path) {
    std::error_code ec;
    fs::path current = fs::absolute(path, ec);
    if (ec) current = path;
    for (int hop = 0; hop < max_link_hops; ++hop) {
        if (!fs::is_symlink(fs::symlink_status(current, ec))) break;
        const fs::path target = fs::read_symlink(current, ec);
        if (ec) break;
        current = target.is_absolute() ? target : current.parent_path() / target;
    }
    // The directories on the way may be links too; weakly_canonical follows those that exist.
    const fs::path canonical = fs::weakly_canonical(current, ec);
    return (ec ? current : canonical).lexically_normal().string();
}

bool same_file(const std::string& a, const std::string& b) {
    struct stat sa {}, sb {};
    const bool a_exists = stat(a.c_str(), &sa) == 0;
    const bool b_exists = stat(b.c_str(), &sb) == 0;
    if (a_exists && b_exists) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    if (a_exists != b_exists) return false;
    return real_path(a) == real_path(b);
}

std::optional<std::string> find_clash(const std::vector<NamedPath>& inputs,
                                      const std::vector<NamedPath>& outputs) {
    const auto quoted = [](const NamedPath& p) { return p.role + " '" + printable(p.path) + "'"; };
    for (std::size_t i = 0; i < outputs.size(); ++i) {
        for (const NamedPath& input : inputs) {
            if (same_file(outputs[i].path, input.path)) {
                return quoted(outputs[i]) + " is the same file as " + quoted(input) +
                       ", which it would overwrite; write to another file";
            }
        }
        for (std::size_t j = 0; j < i; ++j) {
            if (same_file(outputs[i].path, outputs[j].path)) {
                return quoted(outputs[i]) + " and " + quoted(outputs[j]) +
                       " are the same file; give each output its own";
            }
        }
    }
    return std::nullopt;
}

}  // namespace discreel
