#include "hrad/io/exr_writer.h"

#include <vector>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <fmt/format.h>

#include "hrad/core/error.h"
#include "hrad/io/atomic_file.h"

namespace hrad {

void write_exr(const std::string& path, const HdrImage& image) {
  if (image.width <= 0 || image.height <= 0) throw Error(fmt::format("{}: cannot write an empty image", path));
  std::vector<float> rgb(image.pixels.size() * 3);
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) rgb[3 * i + static_cast<std::size_t>(c)] = static_cast<float>(image.pixels[i][c]);
  write_path_atomically(path, [&](const std::string& tmp) {
    try {
      Imf::Header header(image.width, image.height);
      header.compression() = Imf::ZIP_COMPRESSION;
      Imf::FrameBuffer frame;
      const char* names[3] = {"R", "G", "B"};
      for (int c = 0; c < 3; ++c) {
        header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
        frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(rgb.data() + c), 3 * sizeof(float),
                                          3 * sizeof(float) * static_cast<std::size_t>(image.width)));
      }
      Imf::OutputFile file(tmp.c_str(), header);
      file.setFrameBuffer(frame);
      file.writePixels(image.height);
    } catch (const std::exception& e) {
      throw Error(fmt::format("{}: cannot write the OpenEXR file: {}", path, e.what()));
    }
  });
}

HdrImage read_exr(const std::string& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const int width = window.max.x - window.min.x + 1, height = window.max.y - window.min.y + 1;
    std::vector<float> rgb(static_cast<std::size_t>(width) * height * 3, 0.0f);
    Imf::FrameBuffer frame;
    const char* names[3] = {"R", "G", "B"};
    const std::ptrdiff_t origin =
        -(static_cast<std::ptrdiff_t>(window.min.x) + static_cast<std::ptrdiff_t>(window.min.y) * width);
    for (int c = 0; c < 3; ++c)
      frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(rgb.data() + c + 3 * origin),
                                        3 * sizeof(float), 3 * sizeof(float) * static_cast<std::size_t>(width)));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    HdrImage image(width, height);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
      image.pixels[i] = Rgb(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]);
    return image;
  } catch (const std::exception& e) {
    throw Error(fmt::format("{}: cannot read the OpenEXR file: {}", path, e.what()));
  }
}

}  // namespace hrad
