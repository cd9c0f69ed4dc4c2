#include "jpeg_encoder.hpp"

#include <turbojpeg.h>

#include <algorithm>
#include <stdexcept>

namespace tourmap::render {

JpegEncoder::JpegEncoder() : handle_(tjInitCompress()) {
  if (!handle_) throw std::runtime_error("jpeg: cannot create a TurboJPEG compressor");
}

JpegEncoder::~JpegEncoder() {
  tjFree(buffer_);
  if (handle_) tjDestroy(static_cast<tjhandle>(handle_));
}

void JpegEncoder::encode_rgba_append(const std::uint8_t* rgba, int width, int height, int quality, bool bottom_up,
                                     std::string& out) {
  if (width <= 0 || height <= 0) throw std::runtime_error("jpeg: empty image");
  quality = std::clamp(quality, 1, 100);
  const unsigned long worst = tjBufSize(width, height, TJSAMP_420);
  if (worst == static_cast<unsigned long>(-1)) throw std::runtime_error("jpeg: image too large");
  if (worst > buffer_size_) {
    tjFree(buffer_);
    buffer_ = tjAlloc(static_cast<int>(worst));
    buffer_size_ = buffer_ ? worst : 0;
    if (!buffer_) throw std::runtime_error("jpeg: out of memory");
  }
  unsigned char* target = buffer_;
  unsigned long size = buffer_size_;
  // NOREALLOC: TurboJPEG writes into our buffer, which tjBufSize guarantees is large enough.
  const int flags = TJFLAG_FASTDCT | TJFLAG_NOREALLOC | (bottom_up ? TJFLAG_BOTTOMUP : 0);
  if (tjCompress2(static_cast<tjhandle>(handle_), rgba, width, 0, height, TJPF_RGBA, &target, &size, TJSAMP_420,
                  quality, flags) != 0)
    throw std::runtime_error(std::string("jpeg: ") + tjGetErrorStr2(static_cast<tjhandle>(handle_)));
  out.append(reinterpret_cast<const char*>(target), size);
}

std::string JpegEncoder::encode_rgba(const std::uint8_t* rgba, int width, int height, int quality, bool bottom_up) {
  std::string bytes;
  encode_rgba_append(rgba, width, height, quality, bottom_up, bytes);
  return bytes;
}

}  // namespace tourmap::render
