#pragma once
// TUM RGB-D sequences (rgb.txt, depth.txt, rgb/*.png, depth/*.png) for the TUM reader's tests and
// fuzz seeds.
//
// rgb at 10.000, 10.033, 10.067, 10.100; depth at 10.005, 10.040, 10.070, 10.300: the last of each
// has no partner within 20 ms. Colour frame i is (x * 8, y * 8, i * 40); depth raw
// 5 * (1000 + x + 10 y) (TUM's 5000 units per metre), i.e. 1000 + x + 10 y millimetres.

#include <filesystem>

#include "simtree/io/image_io.h"

namespace simtree::test {

constexpr int kTumWidth = 32;
constexpr int kTumHeight = 24;

RgbImage TumColor(int frame);
DepthImage TumRawDepth(int width = kTumWidth, int height = kTumHeight);

// Writes the sequence into `dir` (made if missing) and returns it.
std::filesystem::path WriteTumSequence(const std::filesystem::path& dir);

}  // namespace simtree::test
