#pragma once
// A picture for people: the photo with the extracted profile in red and the compared circle.
#include "demfit/imaging/image.hpp"
#include "demfit/imaging/surface.hpp"

namespace demfit::imaging {

// The photo in grey with the compared circle (radius profile.compared_radius) drawn in blue and
// the profile as a red polyline (3 px wide). Image size as the photo's.
RgbImage draw_overlay(const GreyImage& photo, const DrumFrame& frame, const SurfaceProfile& profile);

// Draws a polyline of a profile in the given colour into an image spanning frame.diameter.
void draw_profile(RgbImage& image, const DrumFrame& frame, const SurfaceProfile& profile, std::uint8_t red,
                  std::uint8_t green, std::uint8_t blue);

}  // namespace demfit::imaging
