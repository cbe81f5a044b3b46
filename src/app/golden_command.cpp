#include "golden_command.hpp"

#include <unistd.h>

#include <chrono>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>

#include "discreel/commit.hpp"
#include "discreel/printable.hpp"
#include "discreel/encode.hpp"
#include "discreel/parse_number.hpp"
#include "discreel/job.hpp"
#include "discreel/render.hpp"
#include "exit_codes.hpp"
#include "golden_compare.hpp"
#include "golden_junit.hpp"
#include "golden_metadata.hpp"
#include "golden_report.hpp"
#include "progress.hpp"
#include "signals.hpp"
#include "run_support.hpp"

namespace discreel::app {
namespace {

namespace fs = std::filesystem;

struct LoadedScene {
    std::string path;   // as the user typed it
    scene::Scene scene;
};

// The directory of a failure's files and report: --results, else golden-results beside --dir.
fs::path results_dir(const GoldenOptions& o) {
    if (o.results) return *o.results;
    // Beside the goldens, however --dir is written: "goldens/" and "." name a directory too.
    fs::path dir = fs::path(o.dir).lexically_normal();
    if (dir.filename().empty()) dir = dir.parent_path();
    if (dir.empty() || dir.filename() == "." || dir.filename() == "..") {
        dir = fs::absolute(dir.empty() ? fs::path(".") : dir).lexically_normal();
        if (dir.filename().empty()) dir = dir.parent_path();
    }
    return dir.parent_path() / "golden-results";
}

// Whether `inner` is `outer` or inside it, through links and relative spellings.
bool inside(const fs::path& inner, const fs::path& outer) {
    std::error_code ignored;
    const fs::path a = fs::weakly_canonical(inner, ignored);
    const fs::path b = fs::weakly_canonical(outer, ignored);
    auto [ai, bi] = std::mismatch(a.begin(), a.end(), b.begin(), b.end());
    return bi == b.end() || (std::next(bi) == b.end() && bi->empty());
}

std::optional<std::string> check_options(const GoldenOptions& o) {
    if (o.dir.empty()) return "--dir is required: the directory that holds the goldens";
    if (!(o.tolerance >= 0 && o.tolerance <= 1))
        return "--tolerance must be between 0 (exact colours) and 1 (any colour)";
    if (o.max_diff_pixels && *o.max_diff_pixels < 0)
        return "--max-diff-pixels must be 0 or more";
    if (o.max_diff_ratio && !(*o.max_diff_ratio >= 0 && *o.max_diff_ratio <= 1))
        return "--max-diff-ratio must be between 0 and 1";
    if (o.shards < 1 || o.shard < 1 || o.shard > o.shards)
        return "--shard takes K/N with 1 <= K <= N, e.g. 2/4";
    if (o.results && inside(*o.results, o.dir)) {
        return "--results '" + *o.results + "' is inside --dir '" + o.dir +
               "': a failure's files never go among the goldens; give a directory beside it";
    }
    return std::nullopt;
}

// Keeps the golden frames of share `shard` of `shards` (see GoldenOptions::shard); each
// scene's frames end sorted and without repeats, and a scene left with none is dropped.
// Returns how many frames all the shares hold together.
std::size_t keep_shard(std::vector<LoadedScene>& scenes, int shard, int shards) {
    std::size_t index = 0;
    std::vector<LoadedScene> kept;
    for (LoadedScene& loaded : scenes) {
        std::vector<int> frames = loaded.scene.golden_frames;
        std::sort(frames.begin(), frames.end());
        frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
        std::vector<int> mine;
        for (const int frame : frames) {
            if (index++ % static_cast<std::size_t>(shards) == static_cast<std::size_t>(shard - 1)) {
                mine.push_back(frame);
            }
        }
        if (mine.empty()) continue;
        loaded.scene.golden_frames = std::move(mine);
        kept.push_back(std::move(loaded));
    }
    scenes = std::move(kept);
    return index;
}

// One scene's thresholds: its `golden:` block's where it sets them, the command line's else.
struct Thresholds {
    double tolerance = 0.1;
    std::optional<std::int64_t> max_diff_pixels;
    std::optional<double> max_diff_ratio;
};

Thresholds thresholds_of(const GoldenOptions& o, const scene::Scene& scene) {
    const auto& own = scene.golden_thresholds;
    return {.tolerance = own.tolerance.value_or(o.tolerance),
            .max_diff_pixels = own.max_diff_pixels ? own.max_diff_pixels : o.max_diff_pixels,
            .max_diff_ratio = own.max_diff_ratio ? own.max_diff_ratio : o.max_diff_ratio};
}

// How many pixels of a frame may differ: the tighter of the two limits given, none by default.
std::int64_t allowed_differences(const Thresholds& t, std::int64_t pixel_count) {
    if (!t.max_diff_pixels && !t.max_diff_ratio) return 0;
    std::int64_t allowed = std::numeric_limits<std::int64_t>::max();
    if (t.max_diff_pixels) allowed = *t.max_diff_pixels;
    if (t.max_diff_ratio) {
        allowed = std::min(allowed, static_cast<std::int64_t>(
                                        std::floor(*t.max_diff_ratio * pixel_count)));
    }
    return allowed;
}

std::string update_command(const GoldenOptions& o, const std::string& scene_path) {
    std::string command = "discreel golden " + scene_path + " --dir " + o.dir;
    if (o.video.width) {
        command += " --size " + std::to_string(*o.video.width) + "x" +
                   std::to_string(*o.video.height);
    }
    return command + " --update";
}

std::string percent(std::int64_t part, std::int64_t whole) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(2) << 100.0 * static_cast<double>(part) / whole << " %";
    return s.str();
}

std::string fixed(double v, int digits) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(digits) << v;
    return s.str();
}

void remove_if_present(const fs::path& path) {
    std::error_code ignored;
    fs::remove(path, ignored);
}

// One frame's check: its result, whether the golden was missing, and its images for the HTML
// report (filled only when a report is asked for and the frame failed).
struct FrameCheck {
    golden::CaseResult result;
    bool missing = false;
    std::string written;                                  // "wrote X.actual.png and Y.diff.png"
    std::string golden_image, actual_image, diff_image;   // data: URIs
};

// Compares one rendered frame with its golden; writes .actual.png and .diff.png into the
// results directory for a golden it does not match, unless the run will replace that golden
// anyway (--update changed). Fails (run-time error) only when those files cannot be written.
Expected<FrameCheck> check_frame(const GoldenOptions& o, const LoadedScene& loaded, int frame,
                                 const ImageView& actual, const std::string& renderer) {
    const bool write_files = o.update != UpdateMode::changed;
    const std::string name = loaded.scene.name;
    const fs::path scene_dir = fs::path(o.dir) / name;
    const fs::path results = results_dir(o) / name;
    const std::string stem = "frame_" + std::to_string(frame);
    const fs::path golden_png = scene_dir / (stem + ".png");
    const fs::path actual_png = results / (stem + ".actual.png");
    const fs::path diff_png = results / (stem + ".diff.png");
    const Thresholds thresholds = thresholds_of(o, loaded.scene);
    FrameCheck check;
    check.result = {.scene = name, .name = stem, .passed = true, .message = {}, .details = {}};
    golden::CaseResult& result = check.result;
    // The report shows the actual frame, and the golden where there is one to show.
    const auto uri_of = [](const ImageView& image, std::string& uri) -> Status {
        auto made = encode::png_data_uri(image);
        if (!made) return made.error();
        uri = std::move(*made);
        return {};
    };
    const auto add_images = [&](const std::optional<Image>& golden_image,
                                const Image* diff) -> Status {
        // Without --report, a failing run still writes one into the results directory.
        Status made = uri_of(actual, check.actual_image);
        if (made && golden_image) made = uri_of(golden_image->view(), check.golden_image);
        if (made && diff) made = uri_of(diff->view(), check.diff_image);
        return made;
    };
    // No usable golden (none, or a file that is no PNG): this frame fails, the run goes on.
    const auto no_golden = [&](const std::string& message) -> Expected<FrameCheck> {
        result.passed = false;
        result.message = message;
        if (Status s = add_images(std::nullopt, nullptr); !s) return s.error();
        return check;
    };

    std::error_code exists_error;
    if (!fs::exists(golden_png, exists_error)) {
        check.missing = true;
        return no_golden("no golden image " + golden_png.string() + "; create it with: " +
                         update_command(o, loaded.path));
    }
    // The header first: a golden of another size is reported without decoding it, and a
    // file that is no PNG (a directory, /dev/zero) is this frame's failure, not the run's.
    const auto golden_size = encode::read_png_size(golden_png.string());
    if (!golden_size) {
        return no_golden(golden_size.error().message + "; recreate it with: " +
                         update_command(o, loaded.path));
    }
    std::optional<Image> golden;
    if (*golden_size == encode::ImageSize{actual.width, actual.height}) {
        auto decoded = encode::read_png(golden_png.string());
        if (!decoded) {
            return no_golden(decoded.error().message + "; recreate it with: " +
                             update_command(o, loaded.path));
        }
        golden = std::move(*decoded);
    }
    golden::Comparison c;
    if (golden) {
        c = golden::compare_images(actual, golden->view(), {.threshold = thresholds.tolerance});
    } else {
        c.same_size = false;
    }
    const std::int64_t allowed = allowed_differences(thresholds, c.pixel_count);
    if (c.identical || (c.same_size && c.differing_pixels <= allowed)) {
        // A pass clears what an earlier failing run left, so what is there is current.
        remove_if_present(actual_png);
        remove_if_present(diff_png);
        result.message = c.identical ? "identical"
                                     : std::to_string(c.differing_pixels) + " differing pixels, " +
                                           std::to_string(allowed) + " allowed; " +
                                           std::to_string(c.anti_aliased_pixels) +
                                           " anti-aliased pixels ignored";
        return check;
    }

    result.passed = false;
    if (write_files) {
        std::error_code made;
        fs::create_directories(results, made);
        if (made) return Error{"cannot create '" + results.string() + "': " + made.message()};
        if (Status s = encode::write_png(actual_png.string(), actual); !s) return s.error();
    }
    std::string written = "wrote " + actual_png.string();
    if (c.same_size) {
        result.message = std::to_string(c.differing_pixels) + " pixels differ (" +
                         percent(c.differing_pixels, c.pixel_count) + " of " +
                         std::to_string(c.pixel_count) + ", " + std::to_string(allowed) +
                         " allowed; largest colour distance " + fixed(c.max_delta, 3) + ", " +
                         std::to_string(c.anti_aliased_pixels) + " anti-aliased pixels ignored)";
        if (write_files) {
            Status s = encode::write_png(diff_png.string(), c.diff.view());
            if (!s) return s.error();
        }
        written += " and " + diff_png.string();
        if (Status s = add_images(golden, &c.diff); !s) return s.error();
    } else {
        const std::string golden_wxh =
            std::to_string(golden_size->width) + "x" + std::to_string(golden_size->height);
        result.message = "the frame is " + std::to_string(actual.width) + "x" +
                         std::to_string(actual.height) + " but the golden is " + golden_wxh +
                         "; check at the golden's size with --size " + golden_wxh +
                         ", or rewrite the goldens with --update";
        remove_if_present(diff_png);
        std::optional<Image> other_size;
        if (o.report) {
            auto decoded = encode::read_png(golden_png.string());
            if (decoded) other_size = std::move(*decoded);
        }
        if (Status s = add_images(other_size, nullptr); !s) return s.error();
    }
    if (write_files) {
        result.details = result.message + "\n" + written;
        check.written = written;
    }
    if (const auto stored = golden::read_metadata(scene_dir); stored && stored->renderer != renderer) {
        const std::string note = "rendered with a different renderer (stored: " +
                                 stored->renderer + ", now: " + renderer + ")";
        result.message += "; " + note;
        result.details += "\n" + note;
    }
    return check;
}

std::string frame_count_text(std::size_t n) {
    return std::to_string(n) + (n == 1 ? " frame" : " frames");
}

std::string scene_count_text(std::size_t n) {
    return std::to_string(n) + (n == 1 ? " scene" : " scenes");
}

// Every scene is loaded before any is rendered: a typo in the last one costs nothing. Prints
// the problems and returns nothing when a scene is bad.
std::optional<std::vector<LoadedScene>> load_scenes(const GoldenOptions& o, std::ostream& err) {
    std::vector<LoadedScene> scenes;
    bool all_loaded = true;
    std::map<std::string, std::string> path_of_name;
    for (const std::string& path : o.scene_paths) {
        scene::LoadResult loaded = scene::load_scene_file(path, o.limits, o.video.duration,
                                                            o.overrides);
        if (!report_diagnostics(loaded, err)) {
            all_loaded = false;
            continue;
        }
        if (auto problem = apply_overrides(loaded.scene, o.video, o.limits)) {
            report_error(err, *problem);
            return std::nullopt;
        }
        // A check renders at the size the goldens were made at (golden.txt), unless --size
        // says otherwise; --update (all) renders what the scene (or --size) says now.
        if (!o.video.width && o.update != UpdateMode::all) {
            const auto stored = golden::read_metadata(fs::path(o.dir) / loaded.scene.name);
            if (stored && stored->width > 0 && stored->height > 0) {
                VideoOverrides recorded;
                recorded.width = stored->width;
                recorded.height = stored->height;
                if (auto problem = apply_overrides(loaded.scene, recorded, o.limits)) {
                    report_error(err, (fs::path(o.dir) / loaded.scene.name /
                                       golden::metadata_file_name).string() +
                                          ": the recorded size is not usable: " + *problem);
                    return std::nullopt;
                }
            }
        }
        const auto [earlier, fresh] = path_of_name.emplace(loaded.scene.name, path);
        if (!fresh) {
            report_error(err, earlier->second + " and " + path + " are both named '" +
                                  loaded.scene.name + "'; their goldens would share " +
                                  (fs::path(o.dir) / loaded.scene.name).string());
            return std::nullopt;
        }
        scenes.push_back({path, std::move(loaded.scene)});
    }
    if (!all_loaded) return std::nullopt;
    return scenes;
}

// What an --update run has written but not yet made visible. Every golden and golden.txt of
// the run is committed together at its end, so a failure or Ctrl-C leaves the old set whole.
struct PendingGoldens {
    std::vector<OutputFile> images;
    std::vector<AtomicTextFile> metadata;
    // Deleted once the rest is committed: what an earlier failing check left of a frame now
    // written, and the goldens (with their results) of frames their scene no longer lists.
    std::vector<fs::path> stale;
    std::size_t removed_goldens = 0;   // of those goldens

    Status commit() {
        std::vector<OutputFile*> files;
        for (OutputFile& image : images) files.push_back(&image);
        for (AtomicTextFile& text : metadata) files.push_back(&text.file());
        if (Status committed = commit_together(files); !committed) return committed;
        for (const fs::path& path : stale) remove_if_present(path);
        return {};
    }
};

// The frames of the goldens in `scene_dir` (frame_N.png) that are not in `frames` (sorted).
std::vector<int> goldens_not_listed(const fs::path& scene_dir, const std::vector<int>& frames) {
    std::vector<int> out;
    std::error_code error;
    for (fs::directory_iterator it(scene_dir, error), end; !error && it != end;
         it.increment(error)) {
        const std::string name = it->path().filename().string();
        constexpr std::string_view prefix = "frame_", suffix = ".png";
        if (name.size() <= prefix.size() + suffix.size() || name.rfind(prefix, 0) != 0 ||
            name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) {
            continue;
        }
        const auto frame = parse_whole<int>(std::string_view(name).substr(
            prefix.size(), name.size() - prefix.size() - suffix.size()));
        if (frame && "frame_" + std::to_string(*frame) + ".png" == name &&
            !std::binary_search(frames.begin(), frames.end(), *frame)) {
            out.push_back(*frame);
        }
    }
    std::sort(out.begin(), out.end());
    return out;
}

// --update for one frame: the golden, prepared to be committed with all the others.
Expected<golden::CaseResult> write_golden(const fs::path& scene_dir, const fs::path& results_dir,
                                          const std::string& scene, int frame,
                                          const ImageView& image, PendingGoldens& pending) {
    const std::string stem = (scene_dir / ("frame_" + std::to_string(frame))).string();
    auto file = encode::prepare_png(stem + ".png", image);
    if (!file) return file.error();
    pending.images.push_back(std::move(*file));
    const std::string results = (results_dir / ("frame_" + std::to_string(frame))).string();
    pending.stale.emplace_back(results + ".actual.png");
    pending.stale.emplace_back(results + ".diff.png");
    return golden::CaseResult{.scene = scene,
                              .name = "frame_" + std::to_string(frame),
                              .passed = true,
                              .message = "wrote " + printable(stem) + ".png",
                              .details = {}};
}

// Renders one scene's golden frames and checks (or, with --update, writes) each, printing a
// line per frame and appending to `results`. Fails only at run time (GL, files).
// Frames are simulated up to each scene's last golden frame; that is where the time goes, so
// progress counts simulated frames over all scenes.
struct GoldenProgress {
    ProgressMeter meter;
    std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
    int done = 0;

    void frame_done() {
        ++done;
        meter.update(done, std::chrono::duration<double>(std::chrono::steady_clock::now() - started)
                               .count());
    }
};

int frames_to_simulate(const LoadedScene& loaded) {
    const std::vector<int>& frames = loaded.scene.golden_frames;
    return frames.empty() ? 0 : *std::max_element(frames.begin(), frames.end()) + 1;
}

Status run_scene(const GoldenOptions& o, const LoadedScene& loaded, std::ostream& out,
                 std::vector<golden::CaseResult>& results,
                 std::vector<golden::ReportFrame>& report, GoldenProgress& progress,
                 PendingGoldens& pending) {
    const scene::Scene& scene = loaded.scene;
    auto renderer =
        render::Renderer::create({.width = scene.video.width, .height = scene.video.height});
    if (!renderer) return renderer.error();
    const fs::path scene_dir = fs::path(o.dir) / scene.name;
    const bool writes = o.update != UpdateMode::none;
    if (writes) {
        std::error_code made;
        fs::create_directories(scene_dir, made);
        if (made) return Error{"cannot create '" + scene_dir.string() + "': " + made.message()};
    }

    std::vector<int> frames = scene.golden_frames;
    std::sort(frames.begin(), frames.end());
    frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
    job::Playback playback(scene);
    bool wrote_any = false;
    auto case_started = std::chrono::steady_clock::now();
    const auto check_one = [&](int frame, const render::FrameScene& view) -> Status {
        auto image = renderer->draw(view);
        if (!image) return image.error();
        if (stop_signal() != 0) return Error{"interrupted"};
        FrameCheck check;
        if (o.update != UpdateMode::all) {
            auto checked = check_frame(o, loaded, frame, *image, renderer->renderer_info());
            if (!checked) return checked.error();
            check = std::move(*checked);
        }
        // --update writes every golden; =changed those missing or no longer matching;
        // =missing those missing. A frame checked and passed is left as it is.
        const bool write = o.update == UpdateMode::all ||
                           (!check.result.passed && (o.update == UpdateMode::changed ||
                                                     (o.update == UpdateMode::missing &&
                                                      check.missing)));
        if (write) {
            auto written = write_golden(scene_dir, results_dir(o) / scene.name, scene.name, frame,
                                        *image, pending);
            if (!written) return written.error();
            if (!check.result.passed) written->message += " (was: " + check.result.message + ")";
            check = FrameCheck{};
            check.result = std::move(*written);
            wrote_any = true;
        }
        golden::CaseResult& result = check.result;
        result.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - case_started).count();
        progress.meter.finish();   // a result line must not land in the middle of the bar
        out << printable(scene.name) << " frame " << frame << ": ";
        if (write) {
            out << result.message << '\n';
        } else if (result.passed) {
            out << "ok (" << result.message << ")\n";
        } else {
            // The line names what it wrote, so the files to look at are at hand.
            out << "FAILED: " << result.message
                << (check.written.empty() ? "" : "; " + check.written) << '\n';
        }
        report.push_back({.scene = scene.name,
                          .frame = result.name,
                          .passed = result.passed,
                          .written = write,
                          .message = result.message,
                          .golden_image = std::move(check.golden_image),
                          .actual_image = std::move(check.actual_image),
                          .diff_image = std::move(check.diff_image)});
        results.push_back(std::move(result));
        case_started = std::chrono::steady_clock::now();
        return {};
    };
    // Trails and the follow camera remember earlier frames: the playback shows them every one.
    const Status played = frames.empty() ? Status{} : playback.play(
        {.last = frames.back(),
         .drawn = [&](int frame) { return std::binary_search(frames.begin(), frames.end(), frame); },
         .look = true,
         .should_stop = [] { return stop_signal() != 0; },
         .until = {}},
        [&](const job::ShownFrame& shown) -> Status {
            progress.frame_done();
            return shown.view != nullptr ? check_one(shown.frame, *shown.view) : Status{};
        });
    if (stop_signal() != 0) return Error{"interrupted"};
    if (!played) return played.error();
    // An update leaves no golden of a frame the scene no longer lists (a shard sees only part
    // of the frames, so it leaves them).
    if (writes && o.shards == 1) {
        for (const int frame : goldens_not_listed(scene_dir, frames)) {
            const std::string stem = "frame_" + std::to_string(frame);
            pending.stale.push_back(scene_dir / (stem + ".png"));
            pending.stale.push_back(results_dir(o) / scene.name / (stem + ".actual.png"));
            pending.stale.push_back(results_dir(o) / scene.name / (stem + ".diff.png"));
            ++pending.removed_goldens;
            out << printable(scene.name) << " frame " << frame << ": removed "
                << printable((scene_dir / (stem + ".png")).string())
                << " (the scene no longer lists this frame)\n";
        }
    }
    // golden.txt records how the goldens were made: rewritten whenever one of them is.
    if (!writes || (o.update != UpdateMode::all && !wrote_any)) return {};
    auto metadata = golden::prepare_metadata(scene_dir, {.discreel_version = DISCREEL_VERSION,
                                                         .renderer = renderer->renderer_info(),
                                                         .width = scene.video.width,
                                                         .height = scene.video.height});
    if (!metadata) return metadata.error();
    pending.metadata.push_back(std::move(*metadata));
    return {};
}

}  // namespace

int run_golden(const GoldenOptions& o, std::ostream& out, std::ostream& err) {
    if (auto problem = check_options(o)) {
        report_error(err, *problem);
        return exit_bad_input;
    }
    auto scenes = load_scenes(o, err);
    if (!scenes) return exit_bad_input;
    if (o.shards > 1) {
        const std::size_t all = keep_shard(*scenes, o.shard, o.shards);
        // More shards than frames: this one has nothing to check, which is no failure (its
        // JUnit file, if asked for, holds no case).
        if (scenes->empty()) {
            out << "golden: shard " << o.shard << '/' << o.shards << " has no frames: the run has "
                << frame_count_text(all) << " in all, dealt out to " << o.shards << " shards\n";
        }
    }
    // The reports' directories are made now: one that cannot be fails before any rendering.
    std::vector<NamedPath> inputs, reports;
    for (const std::string& path : o.scene_paths) inputs.push_back({"the scene", path});
    if (o.junit) reports.push_back({"--junit", *o.junit});
    if (o.report) reports.push_back({"--report", *o.report});
    if (!check_distinct_files(inputs, reports, err)) return exit_bad_input;
    if (!make_output_directories(reports, err)) return exit_runtime_failure;
    const auto create = [&](const std::optional<std::string>& path,
                            std::optional<AtomicTextFile>& file) {
        if (!path) return true;
        auto created = AtomicTextFile::create(*path);
        if (!created) {
            report_error(err, created.error().message);
            return false;
        }
        file.emplace(std::move(*created));
        return true;
    };
    std::optional<AtomicTextFile> junit, html;
    if (!create(o.junit, junit) || !create(o.report, html)) return exit_runtime_failure;

    int total_frames = 0;
    for (const LoadedScene& loaded : *scenes) total_frames += frames_to_simulate(loaded);
    GoldenProgress progress{
        .meter = ProgressMeter(err, pick_progress_style(false, o.progress, isatty(STDERR_FILENO) == 1),
                               total_frames)};
    std::vector<golden::CaseResult> results;
    std::vector<golden::ReportFrame> report;
    PendingGoldens pending;
    const bool writes = o.update != UpdateMode::none;
    for (const LoadedScene& loaded : *scenes) {
        if (Status s = run_scene(o, loaded, out, results, report, progress, pending); !s) {
            progress.meter.finish();
            if (stop_signal() != 0) {
                err << "discreel: interrupted; "
                    << (writes ? "no golden was written" : "no report was written") << '\n';
                return exit_interrupted_base + stop_signal();
            }
            report_error(err, s.error().message);
            return exit_runtime_failure;
        }
    }
    progress.meter.finish();
    if (writes) {
        if (Status s = pending.commit(); !s) {
            report_error(err, s.error().message);
            return exit_runtime_failure;
        }
    }
    const auto commit_report = [&](std::optional<AtomicTextFile>& file, const std::string& text) {
        if (!file) return true;
        file->write(text);
        if (Status s = file->commit(); !s) {
            report_error(err, s.error().message);
            return false;
        }
        return true;
    };
    const auto failed = static_cast<std::size_t>(std::count_if(
        results.begin(), results.end(), [](const golden::CaseResult& r) { return !r.passed; }));
    // Without --report, a failing check writes its report among the results.
    std::string default_report;
    if (!o.report && failed > 0 && o.update != UpdateMode::changed) {
        default_report = (results_dir(o) / "report.html").string();
        std::error_code made;
        fs::create_directories(results_dir(o), made);
        if (!create(default_report, html)) return exit_runtime_failure;
    }
    if (!commit_report(junit, golden::junit_xml("discreel golden", results)) ||
        !commit_report(html, golden::html_report("discreel golden: " + o.dir, scenes->size(),
                                                 report))) {
        return exit_runtime_failure;
    }
    progress.meter.done(std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                                      progress.started)
                            .count());

    const auto written = static_cast<std::size_t>(std::count_if(
        report.begin(), report.end(), [](const golden::ReportFrame& f) { return f.written; }));
    if (o.update == UpdateMode::all) {
        out << "golden: wrote " << frame_count_text(results.size()) << " of "
            << scene_count_text(scenes->size()) << " to " << printable(o.dir);
        if (pending.removed_goldens > 0)
            out << ", removed " << frame_count_text(pending.removed_goldens);
        out << '\n';
        return exit_ok;
    }
    out << "golden: " << frame_count_text(results.size()) << " of "
        << scene_count_text(scenes->size()) << ": " << results.size() - failed - written
        << " passed, " << failed << " failed";
    if (writes) out << ", " << written << " written";
    if (pending.removed_goldens > 0) out << ", " << pending.removed_goldens << " removed";
    out << '\n';
    if (!default_report.empty()) out << "golden: report: " << printable(default_report) << '\n';
    return failed == 0 ? exit_ok : exit_golden_mismatch;
}

}  // namespace discreel::app
