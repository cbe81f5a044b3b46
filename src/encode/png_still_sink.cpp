#include "png_still_sink.hpp"

#include <string>
#include <utility>

#include "discreel/output_file.hpp"
#include "png_codec.hpp"

namespace discreel::encode {
namespace {

class PngStillSink final : public Sink {
public:
    PngStillSink(const SinkDef& def, OutputFile file) : def_(def), file_(std::move(file)) {}

    Status write(const ImageView& frame) override {
        if (finished_) {
            return write_error(def_.path, "the sink is already finished");
        }
        if (has_frame_) {
            return write_error(def_.path, "a PNG still takes exactly one frame, got a second");
        }
        if (frame.width != def_.width || frame.height != def_.height) {
            return write_error(def_.path, "frame is " + std::to_string(frame.width) + "x" +
                                              std::to_string(frame.height) + " but the image is " +
                                              std::to_string(def_.width) + "x" +
                                              std::to_string(def_.height));
        }
        auto png = encode_png(frame);
        if (!png) {
            return write_error(def_.path, png.error().message);
        }
        if (auto written = file_.write_all(png->data(), png->size()); !written) {
            return written;
        }
        has_frame_ = true;
        return {};
    }

    std::vector<OutputFile*> files() override { return {&file_}; }

    Status seal() override {
        if (finished_) {
            return write_error(def_.path, "the sink is already finished");
        }
        if (!has_frame_) {
            return write_error(def_.path, "a PNG still takes exactly one frame, got none");
        }
        finished_ = true;
        return file_.seal();
    }

private:
    SinkDef def_;
    OutputFile file_;
    bool has_frame_ = false;
    bool finished_ = false;
};

}  // namespace

Expected<std::unique_ptr<Sink>> open_png_still_sink(const SinkDef& def) {
    if (def.width <= 0 || def.height <= 0) {
        return write_error(def.path, "image size " + std::to_string(def.width) + "x" +
                                         std::to_string(def.height) + " is empty");
    }
    auto file = OutputFile::create(def.path);
    if (!file) {
        return file.error();
    }
    return std::unique_ptr<Sink>(std::make_unique<PngStillSink>(def, std::move(*file)));
}

}  // namespace discreel::encode
