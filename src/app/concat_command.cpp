// `discreel concat DIR -o OUT`: the segments one render wrote with --segment, joined into the
// file a whole render writes, byte for byte.
#include <string_view>

#include "commands.hpp"
#include "discreel/commit.hpp"
#include "discreel/encode.hpp"
#include "discreel/file_identity.hpp"
#include "discreel/printable.hpp"
#include "exit_codes.hpp"
#include "run_support.hpp"

namespace discreel::app {

int run_concat(const ConcatOptions& o, std::ostream& out, std::ostream& err) {
    auto set = encode::find_segments(o.dir);
    if (!set) {
        report_error(err, set.error().message);
        return exit_bad_input;
    }
    // The output must not be one of the files it is made from.
    std::vector<NamedPath> inputs;
    for (const std::string& path : set->paths) inputs.push_back({"segment", path});
    for (const std::string& path : set->sound) inputs.push_back({"sound", path});
    if (const auto clash = find_clash(inputs, {{"-o", o.output}})) {
        report_error(err, *clash);
        return exit_bad_input;
    }
    auto file = OutputFile::create(o.output);
    if (!file) {
        report_error(err, file.error().message);
        return exit_runtime_failure;
    }
    if (Status joined = encode::join_segments(*set, *file); !joined) {
        // A problem of the output file is the machine's; any other is the segments'.
        const bool writing = std::string_view(joined.error().message).starts_with("cannot write '");
        report_error(err, joined.error().message);
        return writing ? exit_runtime_failure : exit_bad_input;
    }
    if (Status committed = file->commit(); !committed) {
        report_error(err, committed.error().message);
        return exit_runtime_failure;
    }
    if (!o.quiet) {
        out << "wrote " << printable(o.output) << ": " << set->paths.size()
            << (set->paths.size() == 1 ? " segment" : " segments") << " joined\n";
    }
    return standard_output_ok(out, err) ? exit_ok : exit_runtime_failure;
}

}  // namespace discreel::app
