#include "offscreen_target.hpp"

#include <cassert>
#include <cstddef>
#include <string>

namespace discreel::render {

Expected<OffscreenTarget> OffscreenTarget::create(int width, int height) {
    OffscreenTarget target;
    target.width_ = width;
    target.height_ = height;
    target.color_ = GlRenderbuffer::generate();
    glBindRenderbuffer(GL_RENDERBUFFER, target.color_.id());
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    target.framebuffer_ = GlFramebuffer::generate();
    glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer_.id());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              target.color_.id());
    if (GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        status != GL_FRAMEBUFFER_COMPLETE) {
        return Error{"off-screen framebuffer is incomplete (status " + std::to_string(status) +
                     ")"};
    }
    glViewport(0, 0, width, height);
    return target;
}

void OffscreenTarget::read(std::span<std::uint8_t> out) const {
    assert(out.size() >= std::size_t{4} * static_cast<std::size_t>(width_) *
                             static_cast<std::size_t>(height_));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, out.data());
}

}  // namespace discreel::render
