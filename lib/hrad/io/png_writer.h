// 8-bit RGB PNG files through libpng.
#pragma once

#include <string>

#include "hrad/core/image.h"

namespace hrad {

/// Writes `image` to `path` atomically (temporary file + rename); errors are hrad::Error naming `path`.
void write_png(const std::string& path, const Image& image);

/// Reads a PNG into 8-bit RGB (palette, grey and 16-bit images are converted, alpha dropped).
/// A missing or broken file is an hrad::Error naming `path`.
Image read_png(const std::string& path);

}  // namespace hrad
