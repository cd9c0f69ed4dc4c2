#include "render/jpeg_encoder.hpp"

#include <gtest/gtest.h>
#include <turbojpeg.h>

#include <vector>

namespace tourmap::render {
namespace {

TEST(JpegEncoder, EncodesAndDecodesBackToTheSameColours) {
  const int w = 64, h = 32;
  std::vector<std::uint8_t> rgba(static_cast<std::size_t>(w * h * 4));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      auto* p = &rgba[static_cast<std::size_t>((y * w + x) * 4)];
      p[0] = x < w / 2 ? 220 : 20;  // left red, right blue
      p[1] = 30;
      p[2] = x < w / 2 ? 20 : 220;
      p[3] = 255;
    }
  JpegEncoder enc;
  const std::string jpeg = enc.encode_rgba(rgba.data(), w, h, 90, false);
  ASSERT_GT(jpeg.size(), 100u);
  EXPECT_EQ(static_cast<unsigned char>(jpeg[0]), 0xFF);
  EXPECT_EQ(static_cast<unsigned char>(jpeg[1]), 0xD8);

  tjhandle dec = tjInitDecompress();
  int dw = 0, dh = 0, sub = 0, cs = 0;
  ASSERT_EQ(tjDecompressHeader3(dec, reinterpret_cast<const unsigned char*>(jpeg.data()), jpeg.size(), &dw, &dh, &sub, &cs), 0);
  EXPECT_EQ(dw, w);
  EXPECT_EQ(dh, h);
  std::vector<std::uint8_t> back(static_cast<std::size_t>(w * h * 3));
  ASSERT_EQ(tjDecompress2(dec, reinterpret_cast<const unsigned char*>(jpeg.data()), jpeg.size(), back.data(), w, 0, h,
                          TJPF_RGB, 0), 0);
  tjDestroy(dec);
  const auto* left = &back[static_cast<std::size_t>((h / 2 * w + 4) * 3)];
  const auto* right = &back[static_cast<std::size_t>((h / 2 * w + w - 5) * 3)];
  EXPECT_NEAR(left[0], 220, 12);
  EXPECT_NEAR(right[2], 220, 12);
}

TEST(JpegEncoder, BottomUpFlipsRows) {
  const int w = 16, h = 16;
  std::vector<std::uint8_t> rgba(static_cast<std::size_t>(w * h * 4), 0);
  for (int x = 0; x < w; ++x) rgba[static_cast<std::size_t>(x * 4)] = 255;  // first row red
  JpegEncoder enc;
  const std::string jpeg = enc.encode_rgba(rgba.data(), w, h, 95, true);
  tjhandle dec = tjInitDecompress();
  std::vector<std::uint8_t> back(static_cast<std::size_t>(w * h * 3));
  ASSERT_EQ(tjDecompress2(dec, reinterpret_cast<const unsigned char*>(jpeg.data()), jpeg.size(), back.data(), w, 0, h,
                          TJPF_RGB, 0), 0);
  tjDestroy(dec);
  EXPECT_GT(back[static_cast<std::size_t>(((h - 1) * w + 8) * 3)], 150);  // now the last row
  EXPECT_LT(back[static_cast<std::size_t>((0 * w + 8) * 3)], 100);
}

TEST(JpegEncoder, AppendsAfterAHeaderAndGrowsItsBufferForLargerFrames) {
  JpegEncoder enc;
  std::vector<std::uint8_t> small(16 * 16 * 4, 90), large(300 * 200 * 4);
  for (std::size_t i = 0; i < large.size(); ++i) large[i] = static_cast<std::uint8_t>(i * 7919 % 251);  // noise: big output
  std::string message = "HEAD";
  enc.encode_rgba_append(small.data(), 16, 16, 80, true, message);
  EXPECT_EQ(message.substr(0, 4), "HEAD");
  EXPECT_EQ(message.substr(4), enc.encode_rgba(small.data(), 16, 16, 80, true));
  std::string big;
  enc.encode_rgba_append(large.data(), 300, 200, 95, false, big);
  EXPECT_GT(big.size(), 20000u);  // larger than the first frame's buffer
  tjhandle dec = tjInitDecompress();
  int dw = 0, dh = 0, sub = 0, cs = 0;
  ASSERT_EQ(tjDecompressHeader3(dec, reinterpret_cast<const unsigned char*>(big.data()), big.size(), &dw, &dh, &sub, &cs), 0);
  tjDestroy(dec);
  EXPECT_EQ(dw, 300);
  EXPECT_EQ(dh, 200);
}

TEST(JpegEncoder, RejectsAnEmptyImage) {
  JpegEncoder enc;
  std::uint8_t px[4] = {0, 0, 0, 255};
  EXPECT_THROW(enc.encode_rgba(px, 0, 1, 80, false), std::runtime_error);
}

}  // namespace
}  // namespace tourmap::render
