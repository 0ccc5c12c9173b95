// Images decoded, encoded, sampled and resized; corrupt and oversized images refused with their error.

#include "pdeface/image/image.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace pdeface::image {
namespace {

// A smooth gradient with a disc: what a face photo is made of, for the JPEG's quality to be measurable.
Pixels test_image(std::uint32_t width = 64, std::uint32_t height = 48) {
  Pixels p{width, height, std::vector<std::uint8_t>(std::size_t{width} * height * 3)};
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) {
      const std::size_t i = (std::size_t{y} * width + x) * 3;
      const bool disc = std::hypot(x - width / 2.0, y - height / 2.0) < height / 4.0;
      p.rgb[i] = static_cast<std::uint8_t>(200 * x / width + (disc ? 40 : 0));
      p.rgb[i + 1] = static_cast<std::uint8_t>(150 * y / height + 30);
      p.rgb[i + 2] = static_cast<std::uint8_t>(disc ? 60 : 120);
    }
  return p;
}

double psnr(const Pixels& a, const Pixels& b) {
  double squared = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i)
    squared += std::pow(double(a.rgb[i]) - double(b.rgb[i]), 2);
  return 10 * std::log10(255.0 * 255.0 * static_cast<double>(a.rgb.size()) / squared);
}

TEST(Image, JpegRoundTripKeepsTheImageAtItsQuality) {
  const Pixels original = test_image();
  double last = 0;
  std::size_t last_bytes = 0;
  for (const int quality : {30, 70, 95}) {
    const std::string jpeg = encode_jpeg(original, {.quality = quality});
    const Result<ImageInfo> info = inspect_image(jpeg, "q");
    ASSERT_TRUE(info.ok());
    EXPECT_EQ(info->mime_type, "image/jpeg");
    const Result<Pixels> back = decode(jpeg, "q.jpg");
    ASSERT_TRUE(back.ok()) << back.error().to_string();
    ASSERT_EQ(back->width, original.width);
    ASSERT_EQ(back->height, original.height);
    const double p = psnr(original, *back);
    EXPECT_GT(p, 25.0) << quality;
    EXPECT_GT(p, last) << "a higher quality is closer: " << quality;
    EXPECT_GT(jpeg.size(), last_bytes) << "and larger: " << quality;
    last = p;
    last_bytes = jpeg.size();
  }
}

TEST(Image, CorruptTruncatedAndForeignImagesAreErrors) {
  const std::string jpeg = encode_jpeg(test_image());
  const Result<Pixels> cut = decode(jpeg.substr(0, jpeg.size() / 2), "cut.jpg");
  ASSERT_FALSE(cut);
  EXPECT_EQ(cut.error().source, "cut.jpg");
  EXPECT_EQ(cut.error().code, ErrorCode::Malformed) << cut.error().to_string();
  const Result<Pixels> foreign = decode(std::string("GIF89a") + std::string(40, '\0'), "a.gif");
  ASSERT_FALSE(foreign);
  EXPECT_EQ(foreign.error().code, ErrorCode::UnsupportedFormat);
  // A header declaring more pixels than allowed is refused before anything is decoded.
  const Result<Pixels> bomb = decode(jpeg, "bomb.jpg", 64 * 47);
  ASSERT_FALSE(bomb);
  EXPECT_EQ(bomb.error().code, ErrorCode::CountTooLarge);
}

TEST(Image, SampleIsBilinearBetweenPixelCentresWithTheOriginAtTheBottomLeft) {
  Pixels p{2, 2, {0, 0, 0, 255, 0, 0, /* bottom row */ 0, 255, 0, 0, 0, 255}};
  // (0, 1) is the top left pixel, (1, 0) the bottom right.
  EXPECT_TRUE(sample(p, {0.0f, 1.0f}).isApprox(Eigen::Vector3f(0, 0, 0)));
  EXPECT_TRUE(sample(p, {1.0f, 1.0f}).isApprox(Eigen::Vector3f(1, 0, 0)));
  EXPECT_TRUE(sample(p, {0.0f, 0.0f}).isApprox(Eigen::Vector3f(0, 1, 0)));
  EXPECT_TRUE(sample(p, {1.0f, 0.0f}).isApprox(Eigen::Vector3f(0, 0, 1)));
  EXPECT_TRUE(sample(p, {0.5f, 0.5f}).isApprox(Eigen::Vector3f(0.25f, 0.25f, 0.25f)));
  EXPECT_TRUE(sample(p, {0.25f, 0.75f}).isApprox(Eigen::Vector3f(0, 0, 0))) << "a pixel's centre";
  EXPECT_THROW((void)sample(Pixels{}, {0.5f, 0.5f}), std::invalid_argument);
}

TEST(Image, ResizedPixelsAreTheMeansOfWhatTheyCover) {
  const Pixels p{4, 2, {0, 0, 0, 100, 100, 100, 200, 200, 200, 255, 255, 255,
                        0, 0, 0, 100, 100, 100, 200, 200, 200, 255, 255, 255}};
  const Pixels half = resized(p, 2, 1);
  ASSERT_EQ(half.rgb.size(), 6U);
  EXPECT_EQ(half.rgb[0], 50);
  EXPECT_EQ(half.rgb[3], 228); // (200 + 255) / 2 = 227.5, rounded
  const Pixels same = resized(test_image(), 64, 48);
  EXPECT_EQ(same.rgb, test_image().rgb);
}

TEST(Image, SrgbTransferFunctionsAreInverse) {
  for (const float v : {0.0f, 0.002f, 0.04f, 0.2f, 0.5f, 0.8f, 1.0f})
    EXPECT_NEAR(to_linear(to_srgb(v)), v, 1e-6f);
  EXPECT_NEAR(to_srgb(0.5f), 0.7354f, 1e-4f);
}

} // namespace
} // namespace pdeface::image
