// High-dynamic-range images as OpenEXR files (the Academy's format; OpenEXR from Debian): the
// values a PNG's tone mapping throws away, kept as 32-bit floats per channel.
#pragma once

#include <string>

#include "hrad/core/image.h"

namespace hrad {

/// Writes `image` to `path` as a scan-line OpenEXR file with float channels R, G, B (ZIP
/// compression), atomically; errors are hrad::Error naming `path`.
void write_exr(const std::string& path, const HdrImage& image);

/// Reads the R, G, B channels of an OpenEXR file (any pixel type) into linear RGB. A missing or
/// broken file is an hrad::Error naming `path`.
HdrImage read_exr(const std::string& path);

}  // namespace hrad
