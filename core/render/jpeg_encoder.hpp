#pragma once
// Frame encoding with libjpeg-turbo's TurboJPEG API. One encoder per thread (the handle is
// reused between frames: creating it costs more than encoding a small frame).

#include <cstdint>
#include <string>

namespace tourmap::render {

class JpegEncoder {
 public:
  JpegEncoder();
  ~JpegEncoder();
  JpegEncoder(const JpegEncoder&) = delete;
  JpegEncoder& operator=(const JpegEncoder&) = delete;

  // Encodes tightly packed RGBA pixels. `bottom_up` flips rows (glReadPixels' origin is the
  // bottom-left corner). quality 1..100; chroma subsampling 4:2:0. Throws std::runtime_error.
  std::string encode_rgba(const std::uint8_t* rgba, int width, int height, int quality, bool bottom_up);
  // The same, appended to `out` (e.g. after a message header): the compressed bytes go into a
  // buffer the encoder keeps between frames (sized for the worst case of the largest frame so
  // far), so a stream of frames allocates nothing but `out`.
  void encode_rgba_append(const std::uint8_t* rgba, int width, int height, int quality, bool bottom_up,
                          std::string& out);

 private:
  void* handle_ = nullptr;
  unsigned char* buffer_ = nullptr;  // tjAlloc'ed
  unsigned long buffer_size_ = 0;
};

}  // namespace tourmap::render
