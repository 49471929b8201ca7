// A false-colour isolux plot of a work-plane grid of illuminance (a lighting designer's drawing of
// a task area, e.g. EN 12464-1's): the grid's values, known at its cells' centres, bilinearly
// interpolated at every pixel (held constant beyond the outer centres), coloured in bands between
// round levels (1, 2, 2.5 or 5 times a power of ten), each level's isoline drawn dark where the
// band changes between neighbouring pixels, and on the right a colour bar with every level labelled.
// The rectangle's u axis runs to the right and its v axis up, or down (IsoluxOptions::v_down: so
// that the plot shows the plane as seen from the side its sensors face).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "hrad/core/image.h"

namespace hrad {

/// Round levels strictly between lo and hi: the multiples of the smallest step of the form
/// {1, 2, 2.5, 5} x 10^k not below (hi - lo) / target, so at most `target` of them (none when
/// hi <= lo or either is not finite); a multiple within 1e-6 step of lo or hi is left out.
std::vector<double> isolux_levels(double lo, double hi, int target = 8);

struct IsoluxOptions {
  int long_side = 512;    ///< pixels along the rectangle's longer side
  double aspect = 1.0;    ///< the rectangle's width / height (u extent / v extent)
  int target_levels = 8;  ///< at most this many levels (isolux_levels)
  std::string unit;       ///< written after each label ("lx"); empty for none
  bool v_down = false;    ///< v runs down the plot instead of up
};

struct IsoluxImage {
  Image image;                 ///< the plot, then the colour bar to its right
  int plot_width = 0;          ///< the plot's pixels: [0, plot_width) x [0, image.height)
  std::vector<double> levels;  ///< the isolines, ascending
};

/// The plot of `values` (nu x nv, u fastest, as grid_points makes them). Throws hrad::Error when
/// values.size() != nu * nv or an option is out of range.
IsoluxImage render_isolux(std::span<const double> values, int nu, int nv, const IsoluxOptions& options = {});

/// The band colour of t in [0, 1] (clamped): a perceptually ordered dark-blue to yellow ramp through
/// the anchors of matplotlib's viridis (van der Walt & Smith 2015), linear between them in sRGB.
Rgb8 sequential_colormap(double t);

}  // namespace hrad
