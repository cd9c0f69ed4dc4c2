#include "jpeg_encoder.hpp"

#include <turbojpeg.h>

#include <algorithm>
#include <stdexcept>

namespace tourmap::render {

JpegEncoder::JpegEncoder() : handle_(tjInitCompress()) {
  if (!handle_) throw std::runtime_error("jpeg: cannot create a TurboJPEG compressor");
}

JpegEncoder::~JpegEncoder() {
  if (handle_) tjDestroy(static_cast<tjhandle>(handle_));
}

std::string JpegEncoder::encode_rgba(const std::uint8_t* rgba, int width, int height, int quality, bool bottom_up) {
  if (width <= 0 || height <= 0) throw std::runtime_error("jpeg: empty image");
  quality = std::clamp(quality, 1, 100);
  unsigned char* out = nullptr;
  unsigned long size = 0;
  const int flags = TJFLAG_FASTDCT | (bottom_up ? TJFLAG_BOTTOMUP : 0);
  if (tjCompress2(static_cast<tjhandle>(handle_), rgba, width, 0, height, TJPF_RGBA, &out, &size, TJSAMP_420,
                  quality, flags) != 0) {
    const std::string why = tjGetErrorStr2(static_cast<tjhandle>(handle_));
    tjFree(out);
    throw std::runtime_error("jpeg: " + why);
  }
  std::string bytes(reinterpret_cast<const char*>(out), size);
  tjFree(out);
  return bytes;
}

}  // namespace tourmap::render
