#include "png_sequence_sink.hpp"

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "discreel/output_file.hpp"
#include "png_codec.hpp"

namespace discreel::encode {
namespace {

class PngSequenceSink final : public Sink {
public:
    PngSequenceSink(const SinkDef& def, FramePattern pattern)
        : def_(def), pattern_(std::move(pattern)) {}

    Status write(const ImageView& frame) override {
        if (auto status = usable(); !status) {
            return status;
        }
        const std::string path =
            pattern_.path_of(def_.first_number + static_cast<int>(files_.size()));
        if (frame.width != def_.width || frame.height != def_.height) {
            return write_error(path, "frame is " + std::to_string(frame.width) + "x" +
                                         std::to_string(frame.height) + " but the image is " +
                                         std::to_string(def_.width) + "x" +
                                         std::to_string(def_.height));
        }
        failed_ = true;   // until this frame is safely on disk
        auto file = write_png_to_temporary(path, frame);
        if (!file) {
            return file.error();
        }
        if (auto sealed = file->seal(); !sealed) {
            return sealed;
        }
        files_.push_back(std::move(*file));
        failed_ = false;
        return {};
    }

    std::vector<OutputFile*> files() override {
        std::vector<OutputFile*> all;
        all.reserve(files_.size());
        for (OutputFile& file : files_) all.push_back(&file);
        return all;
    }

    Status seal() override {
        if (auto status = usable(); !status) {
            return status;
        }
        if (files_.empty()) {
            failed_ = true;
            return write_error(def_.path, "no frames were written");
        }
        finished_ = true;   // every frame was sealed as it was written
        return {};
    }

private:
    Status usable() const {
        if (finished_) {
            return write_error(def_.path, "the sink is already finished");
        }
        if (failed_) {
            return write_error(def_.path, "the sink failed earlier and cannot continue");
        }
        return {};
    }

    SinkDef def_;
    FramePattern pattern_;
    std::vector<OutputFile> files_;   // sealed temporary files, one per frame so far
    bool finished_ = false;
    bool failed_ = false;
};

}  // namespace

Expected<std::unique_ptr<Sink>> open_png_sequence_sink(const SinkDef& def, FramePattern pattern) {
    if (def.width <= 0 || def.height <= 0) {
        return write_error(def.path, "image size " + std::to_string(def.width) + "x" +
                                         std::to_string(def.height) + " is empty");
    }
    // Fail now, not after the first frame, when the directory is missing or read-only: the
    // first file is created and dropped again.
    if (auto probe = OutputFile::create(pattern.path_of(def.first_number)); !probe) {
        return probe.error();
    }
    return std::unique_ptr<Sink>(std::make_unique<PngSequenceSink>(def, std::move(pattern)));
}

}  // namespace discreel::encode
