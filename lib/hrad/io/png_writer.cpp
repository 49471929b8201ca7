#include "hrad/io/png_writer.h"

#include <csetjmp>
#include <cstdio>
#include <memory>

#include <fmt/format.h>
#include <png.h>

#include "hrad/core/error.h"
#include "hrad/io/atomic_file.h"

namespace hrad {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const {
    if (f) std::fclose(f);
  }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// libpng's default handlers print to stderr; the caller reports errors itself (naming the file).
void silent_error(png_structp png, png_const_charp) { png_longjmp(png, 1); }
void silent_warning(png_structp, png_const_charp) {}

// libpng reports errors by longjmp; these functions hold no C++ objects with destructors between
// setjmp and the libpng calls, so the jump is safe. They return false on error.
bool write_rows(std::FILE* file, const Image& image, std::vector<png_bytep>& rows) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, silent_error, silent_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, image.width, image.height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

bool read_rows(std::FILE* file, Image* image, std::vector<png_byte>* buffer, std::vector<png_bytep>* rows) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, silent_error, silent_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_init_io(png, file);
  png_read_info(png, info);
  png_set_expand(png);  // palette -> RGB, grey < 8 bits -> 8 bits
  png_set_strip_16(png);
  png_set_strip_alpha(png);
  png_set_gray_to_rgb(png);
  png_read_update_info(png, info);
  const png_uint_32 width = png_get_image_width(png, info), height = png_get_image_height(png, info);
  if (png_get_rowbytes(png, info) != 3 * width) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  image->width = static_cast<int>(width);
  image->height = static_cast<int>(height);
  buffer->resize(static_cast<std::size_t>(3) * width * height);
  rows->resize(height);
  for (png_uint_32 y = 0; y < height; ++y) (*rows)[y] = buffer->data() + static_cast<std::size_t>(3) * width * y;
  png_read_image(png, rows->data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

}  // namespace

void write_png(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * image.height)
    throw Error(fmt::format("{}: cannot write an empty or inconsistent {}x{} image", path, image.width, image.height));
  static_assert(sizeof(Rgb8) == 3, "Image pixels are packed RGB triples");
  std::vector<png_bytep> rows(image.height);
  for (int y = 0; y < image.height; ++y)
    rows[y] = const_cast<png_bytep>(
        reinterpret_cast<const png_byte*>(&image.pixels[static_cast<std::size_t>(y) * image.width]));
  write_path_atomically(path, [&](const std::string& tmp) {
    File file(std::fopen(tmp.c_str(), "wb"));
    if (!file) throw Error(fmt::format("{}: cannot open for writing", path));
    if (!write_rows(file.get(), image, rows)) throw Error(fmt::format("{}: PNG encoding failed", path));
    if (std::fflush(file.get()) != 0) throw Error(fmt::format("{}: write failed", path));
  });
}

Image read_png(const std::string& path) {
  File file(std::fopen(path.c_str(), "rb"));
  if (!file) throw Error(fmt::format("{}: cannot open PNG", path));
  png_byte header[8] = {};
  if (std::fread(header, 1, 8, file.get()) != 8 || png_sig_cmp(header, 0, 8) != 0)
    throw Error(fmt::format("{}: not a PNG file", path));
  std::rewind(file.get());
  Image image;
  std::vector<png_byte> buffer;
  std::vector<png_bytep> rows;
  if (!read_rows(file.get(), &image, &buffer, &rows)) throw Error(fmt::format("{}: broken PNG file", path));
  image.pixels.resize(static_cast<std::size_t>(image.width) * image.height);
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = {buffer[3 * i], buffer[3 * i + 1], buffer[3 * i + 2]};
  return image;
}

}  // namespace hrad
