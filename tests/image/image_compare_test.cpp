// lib/image/image_compare.cpp: the tolerance rule of reference-image tests.
#include "simbob/tool/image_compare.h"

#include <catch2/catch.hpp>

#include "image_test_util.h"

using simbob::compareImages;
using simbob::Image;
using simbob::ImageComparison;
using simbob::ImageTolerance;
using simbob_test::movingSquares;

TEST_CASE("compareImages: the same image, and one-step shade noise, match", "[image][compare]") {
  const Image ref = movingSquares(160, 120, 3);
  ImageComparison r = compareImages(ref, ref);
  CHECK(r.matches);
  CHECK(r.differing == 0);
  CHECK(r.max_difference == 0);
  CHECK(r.pixels == 160 * 120);
  CHECK(r.first_x == -1);
  CHECK(r.summary() == "0 of 19200 pixels (0.00%) differ, max channel difference 0");

  // Every channel of every pixel off by one, as one rasteriser rounds against another.
  Image noisy = ref;
  for (size_t i = 0; i < noisy.rgb.size(); ++i)
    noisy.rgb[i] = static_cast<uint8_t>(noisy.rgb[i] ^ (i % 3 == 0 ? 1 : 0));
  r = compareImages(noisy, ref);
  CHECK(r.matches);
  CHECK(r.differing == 0);
  CHECK(r.max_difference == 1);
}

TEST_CASE("compareImages: a wrong colour, a missing object and a moved camera fail", "[image][compare]") {
  const Image ref = movingSquares(160, 120, 3);

  // The red square (16x16 = 256 pixels, 1.3% of the frame) drawn a little less red.
  Image wrong = ref;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x)
      if (wrong.pixel(x, y)[0] == 230) wrong.pixel(x, y)[0] = 200;
  ImageComparison r = compareImages(wrong, ref);
  CHECK_FALSE(r.matches);
  CHECK(r.differing == 256);
  CHECK(r.max_difference == 30);
  CHECK(r.first_x == 20);  // (8 + 4 * 3, 120 / 4)
  CHECK(r.first_y == 30);
  CHECK(r.summary() == "256 of 19200 pixels (1.33%) differ, max channel difference 30, first at (20, 30)");
  // The diff image: red where they differ, the reference dimmed elsewhere.
  REQUIRE(r.diff.width == 160);
  CHECK(r.diff.pixel(20, 30)[0] == 255);
  CHECK(r.diff.pixel(20, 30)[1] == 0);
  CHECK(r.diff.pixel(0, 0)[0] == r.diff.pixel(0, 0)[1]);
  CHECK(r.diff.pixel(0, 0)[0] < 40);

  // The blue square missing: its 144 pixels show the floor.
  const Image without = [&] {
    Image img = movingSquares(160, 120, 3);
    const Image other = movingSquares(160, 120, 40);  // blue square elsewhere, red square elsewhere
    for (int y = 10; y < 22; ++y)
      for (int x = 80; x < 92; ++x)
        for (int c = 0; c < 3; ++c) img.pixel(x, y)[c] = other.pixel(x, y)[c];
    return img;
  }();
  r = compareImages(without, ref);
  CHECK_FALSE(r.matches);
  CHECK(r.differing == 144);

  // The camera turned: the whole picture two pixels to the right.
  Image shifted = ref;
  for (int y = 0; y < 120; ++y)
    for (int x = 159; x >= 2; --x)
      for (int c = 0; c < 3; ++c) shifted.pixel(x, y)[c] = ref.pixel(x - 2, y)[c];
  r = compareImages(shifted, ref);
  CHECK_FALSE(r.matches);
  CHECK(r.differing == 112);  // two columns more or less at either side of both squares: 2 * 2 * (16 + 12)
}

TEST_CASE("compareImages: the limits are inclusive and the sizes must agree", "[image][compare]") {
  const Image ref(100, 100);  // black, 10000 pixels: 0.5% is 50

  Image a = ref;
  for (int x = 0; x < 50; ++x) a.pixel(x, 7)[2] = 8;  // exactly the tolerance: not a difference
  ImageComparison r = compareImages(a, ref);
  CHECK(r.differing == 0);
  CHECK(r.max_difference == 8);

  for (int x = 0; x < 50; ++x) a.pixel(x, 7)[2] = 9;  // 50 differing pixels: still a match
  r = compareImages(a, ref);
  CHECK(r.differing == 50);
  CHECK(r.matches);
  a.pixel(0, 8)[1] = 200;  // the 51st: no longer
  r = compareImages(a, ref);
  CHECK(r.differing == 51);
  CHECK_FALSE(r.matches);
  CHECK(compareImages(a, ref, ImageTolerance{8, 0.0051}).matches);
  CHECK(compareImages(a, ref, ImageTolerance{200, 0.0}).matches);

  r = compareImages(Image(50, 100), ref);
  CHECK_FALSE(r.same_size);
  CHECK_FALSE(r.matches);
  CHECK(r.diff.rgb.empty());
  CHECK(r.summary() == "size 50x100, the reference is 100x100");
}
