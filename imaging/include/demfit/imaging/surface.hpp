#pragma once
// Free-surface profile of a granular bed in a rotating drum, extracted from a square grey image
// that spans the drum's inner diameter in both directions, centred on the drum axis.
//
// Frame: x [m] horizontal, to the right as seen in the picture; z [m] up; origin on the drum axis.
// Pixel centres span -R..+R: for N pixels across, pixel (column i, row j) has its centre at
// x = -R + i h, z = R - j h with h = D / (N - 1) (the GranuDrum photos: 406 px -> 84 mm).
//
// Extraction rule (extract_surface):
//  1. Only pixels whose centre lies inside the compared circle, radius (1 - margin) R, take part
//     (the drawn drum outline and the wall region are ignored).
//  2. Threshold: Otsu's method on the grey levels inside the circle (256 bins), unless
//     `threshold` >= 0 is given. Material is value < threshold (material_is_dark) or
//     value > threshold (inverted contrast, e.g. occupancy images).
//  3. The bed is the set of material pixels 4-connected to the bottom of the compared circle
//     (seeds: material pixels that are the lowest circle pixel of their column, below the axis).
//     Isolated speckles above the bed and holes inside it are thereby ignored.
//  4. In each pixel column the surface is the top of the bed: between its topmost bed pixel and
//     the empty pixel above it, refined to sub-pixel by linear interpolation of the grey level
//     across the threshold. A column has no surface when it holds no bed pixel or when the bed
//     reaches the top of the circle (the surface is not seen inside the compared circle).
//  5. `points` abscissae are placed equally spaced from the first to the last column that has a
//     surface (the usable chord); z there is interpolated linearly between the two neighbouring
//     columns; an abscissa whose neighbouring columns lack a surface is dropped (never NaN).
#include <vector>

#include "demfit/imaging/image.hpp"

namespace demfit::imaging {

struct DrumFrame {
  double diameter = 0.084;  // [m] inner drum diameter spanned by the image in both directions
};

struct ProfileOptions {
  double threshold = -1.0;       // grey level in [0,1] separating material from empty; < 0 = automatic (Otsu)
  bool material_is_dark = true;  // photos: powder dark; false = inverted contrast (occupancy images)
  double margin = 0.1;           // ignore pixels beyond (1 - margin) R from the axis; fraction of R, in [0, 1)
  int points = 41;               // abscissae of the profile, equally spaced across the usable chord region
};

// Free surface in the drum frame (metres). x increasing, all values finite.
struct SurfaceProfile {
  std::vector<double> x;         // [m]
  std::vector<double> z;         // [m] height of the bed's top surface
  double threshold_used = 0.0;   // grey level actually used (Otsu's or the given one)
  double compared_radius = 0.0;  // [m] (1 - margin) R
  double pixel_size = 0.0;       // [m] h = D / (N - 1)
  double material_level = 0.0;   // median grey level of the material pixels inside the compared circle
  double empty_level = 0.0;      // median grey level of the empty pixels inside the compared circle
};

// The occupancy (fraction of time covered) at which a time-averaged picture with these material and
// empty levels crosses the threshold: (threshold - empty) / (material - empty). For an averaged photo
// it says which occupancy threshold of the simulated side means the same surface (0.5 = the
// occupancy_profile_options rule).
double equivalent_occupancy(const SurfaceProfile& profile);

// Throws std::runtime_error (one line naming the image source or option and the fix) for a
// non-square or too small (< 32 px) image, diameter <= 0, options out of range, or when no
// surface is found (all material or all empty inside the compared circle, e.g. an all-dark or
// all-light picture).
SurfaceProfile extract_surface(const GreyImage& image, const DrumFrame& frame, const ProfileOptions& options);

// Otsu's threshold (maximal between-class variance, 256 bins on [0,1]) of the pixels inside the
// circle of radius (1 - margin) R. Throws when those pixels hold a single grey level.
double otsu_threshold(const GreyImage& image, double margin);

// The options for the simulated side (an occupancy image from OccupancyAccumulator): same margin
// and points as the photo's, material = occupancy > 0.5 (covered in more than half the samples).
ProfileOptions occupancy_profile_options(const ProfileOptions& photo_options);

// Position [m] of pixel centre index i (column, or row counted from the top for z) in an image of
// n pixels spanning `diameter`.
double pixel_x(int column, int n, double diameter);
double pixel_z(int row, int n, double diameter);

}  // namespace demfit::imaging
