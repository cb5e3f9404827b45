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
//  5. A drum photo holds one powder bed resting on the drum bottom under one free surface. With
//     `require_single_bed`, the picture is refused when (a) fewer than kMinBedShare of the
//     material pixels inside the circle belong to the bed (the material is scattered: noise, a
//     checkerboard, a texture), (b) fewer than kMinBedSolidity of the circle pixels below the
//     surface are bed (a porous, percolating speckle pattern rather than a bed), or (c) fewer
//     than kMinSurfaceCover of the pixel columns from the first to the last with a surface have one
//     (the surface is broken up rather than continuous across the chord).
//  6. `points` abscissae are placed equally spaced from the first to the last column that has a
//     surface (the usable chord); z there is interpolated linearly between the two neighbouring
//     columns; an abscissa whose neighbouring columns lack a surface is dropped (never NaN).
#include <string>
#include <vector>

#include "demfit/imaging/image.hpp"

namespace demfit::imaging {

// Inner drum diameters accepted [m]. Below 1 mm no drum exists and the frame arithmetic breaks
// down (1e-300 m gave a non-finite angle). The upper end, 100 m, only keeps the arithmetic
// meaningful: a plausible value that is wrong for the drum (84 typed for 84 mm) is refused with the
// field's name by the callers, which know the drum: identify's study preflight compares it with
// the simulated drum, and `demfit target from-image` refuses more than 10 m.
inline constexpr double kMinDrumDiameter = 1e-3;
inline constexpr double kMaxDrumDiameter = 100.0;

// Throws std::runtime_error (one line, prefixed by `what`) unless kMinDrumDiameter <= diameter <=
// kMaxDrumDiameter.
void check_drum_diameter(double diameter, const std::string& what);

struct DrumFrame {
  double diameter = 0.084;  // [m] inner drum diameter spanned by the image in both directions
};

// Bed shape required of a drum photo (rule 5 above), as fractions. The GranuDrum photos give 1.0
// for all three; uniform noise and checkerboards of 1 to 16 px squares give a bed share below
// 0.05; two-level speckle noise, 70 % dark, percolates (share 0.98) but gives a solidity of 0.69
// and a surface cover of 0.42.
inline constexpr double kMinBedShare = 0.8;
inline constexpr double kMinBedSolidity = 0.8;
inline constexpr double kMinSurfaceCover = 0.9;

struct ProfileOptions {
  double threshold = -1.0;         // grey level in [0,1] separating material from empty; < 0 = automatic (Otsu)
  bool material_is_dark = true;    // photos: powder dark; false = inverted contrast (occupancy images)
  double margin = 0.1;             // ignore pixels beyond (1 - margin) R from the axis; fraction of R, in [0, 1)
  int points = 41;                 // abscissae of the profile, equally spaced across the usable chord region
  bool require_single_bed = true;  // refuse a picture without one bed and one free surface (rule 5)
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
  double bed_share = 0.0;        // fraction of the material pixels inside the circle that are bed (rule 5a)
  double bed_solidity = 0.0;     // fraction of the circle pixels below the surface that are bed (rule 5b)
  double surface_cover = 0.0;    // fraction of the columns across the chord that have a surface (rule 5c)
};

// The occupancy (fraction of time covered) at which a time-averaged picture with these material and
// empty levels crosses the threshold: (threshold - empty) / (material - empty). For an averaged photo
// it says which occupancy threshold of the simulated side means the same surface (0.5 = the
// occupancy_profile_options rule).
double equivalent_occupancy(const SurfaceProfile& profile);

// Throws std::runtime_error (one line naming the image source or option and the fix) for a
// non-square or too small (< 32 px) image, a diameter outside [kMinDrumDiameter, kMaxDrumDiameter], options out of
// range, or when no surface is found (all material or all empty inside the compared circle, e.g. an all-dark or
// all-light picture).
SurfaceProfile extract_surface(const GreyImage& image, const DrumFrame& frame, const ProfileOptions& options);

// Otsu's threshold (maximal between-class variance, 256 bins on [0,1]) of the pixels inside the
// circle of radius (1 - margin) R. Throws when those pixels hold a single grey level.
double otsu_threshold(const GreyImage& image, double margin);

// The options for the simulated side (an occupancy image from OccupancyAccumulator): same margin
// and points as the photo's, material = occupancy > 0.5 (covered in more than half the samples).
// The bed-shape rule is not applied: a simulation with few particles may leave a sparse bed, and
// the image is the program's own, not a user's picture.
ProfileOptions occupancy_profile_options(const ProfileOptions& photo_options);

// Position [m] of pixel centre index i (column, or row counted from the top for z) in an image of
// n pixels spanning `diameter`.
double pixel_x(int column, int n, double diameter);
double pixel_z(int row, int n, double diameter);

}  // namespace demfit::imaging
