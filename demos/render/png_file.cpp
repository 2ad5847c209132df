#include "render/png_file.h"

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace adb::render {
namespace {

// libpng reports errors by longjmp back into the function that called setjmp: the handler
// keeps the message, and that function then throws. Nothing that owns memory is created or
// changed between the setjmp and a jump.
struct PngError {
  std::string message;
};

void onError(png_structp png, png_const_charp message) {
  static_cast<PngError*>(png_get_error_ptr(png))->message = message;
  png_longjmp(png, 1);
}
void onWarning(png_structp, png_const_charp) {}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

File openFile(const std::filesystem::path& file, const char* mode) {
  File f(std::fopen(file.string().c_str(), mode));
  if (!f) throw std::runtime_error("cannot open '" + file.string() + "'");
  return f;
}

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& what) {
  throw std::runtime_error("'" + file.string() + "': " + what);
}

}  // namespace

void writePng(const Image& image, const std::filesystem::path& file) {
  File f = openFile(file, "wb");
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.height()));
  for (int y = 0; y < image.height(); ++y) {
    rows[static_cast<std::size_t>(y)] =
        const_cast<png_bytep>(reinterpret_cast<const png_byte*>(&image.at(0, y)));
  }
  PngError error;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, onError, onWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_write_struct(&png, &info);
    fail(file, "libpng could not start");
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    fail(file, "libpng: " + error.message);
  }
  png_init_io(png, f.get());
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width()),
               static_cast<png_uint_32>(image.height()), 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fflush(f.get()) != 0 || std::ferror(f.get())) fail(file, "write failed");
}

Image readPng(const std::filesystem::path& file) {
  File f = openFile(file, "rb");
  png_byte signature[8] = {};
  if (std::fread(signature, 1, 8, f.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0) {
    fail(file, "not a PNG file");
  }
  PngError error;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, onError, onWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_read_struct(&png, &info, nullptr);
    fail(file, "libpng could not start");
  }
  // Filled after setjmp: held on the heap, so that the automatic objects a longjmp returns
  // to are not changed after the setjmp (their values would be indeterminate).
  struct Buffers {
    std::vector<png_byte> data;
    std::vector<png_bytep> rows;
  };
  const auto buffers = std::make_unique<Buffers>();
  std::vector<png_byte>& data = buffers->data;
  std::vector<png_bytep>& rows = buffers->rows;
  png_uint_32 width = 0, height = 0;
  int channels = 0;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    fail(file, "libpng: " + error.message);
  }
  png_init_io(png, f.get());
  png_set_sig_bytes(png, 8);
  png_read_info(png, info);
  width = png_get_image_width(png, info);
  height = png_get_image_height(png, info);
  const int colour = png_get_color_type(png, info);
  if (png_get_bit_depth(png, info) != 8 ||
      (colour != PNG_COLOR_TYPE_RGB && colour != PNG_COLOR_TYPE_RGB_ALPHA)) {
    png_destroy_read_struct(&png, &info, nullptr);
    fail(file, "not an 8-bit RGB or RGBA PNG");
  }
  channels = colour == PNG_COLOR_TYPE_RGB ? 3 : 4;
  data.resize(static_cast<std::size_t>(width) * height * channels);
  rows.resize(height);
  for (png_uint_32 y = 0; y < height; ++y) rows[y] = &data[static_cast<std::size_t>(y) * width * channels];
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  Image image(static_cast<int>(width), static_cast<int>(height));
  for (png_uint_32 y = 0; y < height; ++y) {
    for (png_uint_32 x = 0; x < width; ++x) {
      const png_byte* p = &data[(static_cast<std::size_t>(y) * width + x) * channels];
      image.at(static_cast<int>(x), static_cast<int>(y)) = Rgb{p[0], p[1], p[2]};
    }
  }
  return image;
}

}  // namespace adb::render
