// PNG output through libpng. libpng reports errors by longjmp, which must not
// cross C++ frames that own resources; so the encoder is a C-style function
// that holds none, and C++ error handling starts only after it returns.
#include <png.h>

#include <fmt/format.h>

#include <csetjmp>
#include <cstdio>
#include <string>

#include "common/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/maps/render.hpp"

namespace dsswarm {
namespace {

static_assert(sizeof(Rgb) == 3, "rows are handed to libpng as packed 8-bit RGB");

struct PngSink {
  std::string* bytes = nullptr;  // the encoded file, collected in memory
  char message[256] = {};        // why libpng gave up, if it did
};

void on_png_error(png_structp png, png_const_charp message) {
  auto* sink = static_cast<PngSink*>(png_get_error_ptr(png));
  std::snprintf(sink->message, sizeof sink->message, "%s", message);
  png_longjmp(png, 1);
}

// Warnings do not stop encoding and we have nowhere better to put them.
void on_png_warning(png_structp, png_const_charp) {}

void on_png_write(png_structp png, png_bytep data, png_size_t length) {
  auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
  bool appended = true;
  try {
    sink->bytes->append(reinterpret_cast<const char*>(data), length);
  } catch (...) {
    appended = false;
  }
  // Raised outside the catch block: longjmp out of a handler would leak the exception.
  if (!appended) png_error(png, "out of memory while encoding");
}

void on_png_flush(png_structp) {}

// Encodes `image` into sink.bytes. Returns false with sink.message set on
// failure. Owns no C++ objects, so a longjmp out of libpng skips nothing.
bool encode_rows(const Image& image, PngSink& sink) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, on_png_error, on_png_warning);
  if (png == nullptr) {
    std::snprintf(sink.message, sizeof sink.message, "cannot create the libpng writer");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    std::snprintf(sink.message, sizeof sink.message, "cannot create the libpng info block");
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, &sink, on_png_write, on_png_flush);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y) {
    png_write_row(png, reinterpret_cast<png_const_bytep>(&image.at(0, y)));
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

std::string encode_png(const std::filesystem::path& path, const Image& image) {
  const auto fail = [&](const std::string& what) {
    throw InputError(fmt::format("cannot write PNG {}: {}", path.string(), what));
  };
  if (image.width <= 0 || image.height <= 0) fail(fmt::format("image is empty ({}x{})", image.width, image.height));
  if (image.width > kMaxImageSide || image.height > kMaxImageSide) {
    fail(fmt::format("image {}x{} is larger than {} pixels a side", image.width, image.height, kMaxImageSide));
  }
  if (image.pixels.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height)) {
    fail(fmt::format("image has {} pixels, expected {}x{}", image.pixels.size(), image.width, image.height));
  }
  std::string bytes;
  PngSink sink;
  sink.bytes = &bytes;
  if (!encode_rows(image, sink)) fail(fmt::format("libpng: {}", sink.message));
  return bytes;
}

void write_png(const std::filesystem::path& path, const Image& image) {
  write_file_atomically(path, encode_png(path, image));
}

}  // namespace dsswarm
