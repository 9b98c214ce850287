// PNG files through libpng's simplified API (png_image_*): errors come back as
// return codes with a message, so no setjmp/longjmp crosses C++ frames.
#include <png.h>

#include <cstring>

#include "vgd/core/diagnostics.hpp"
#include "vgd/core/file.hpp"
#include "vgd/render/image.hpp"

namespace vgd::render {

std::string encode_png(const Image& image) {
  VGD_ASSERT(!image.empty(), "cannot encode an empty image");
  VGD_ASSERT(image.rgba.size() == static_cast<std::size_t>(image.width) * image.height * 4,
             "the image's pixel buffer does not match its size");
  // Opaque images are stored as RGB: a quarter smaller.
  bool opaque = true;
  for (std::size_t i = 3; i < image.rgba.size() && opaque; i += 4) opaque = image.rgba[i] == 255;

  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGBA;
  std::vector<std::uint8_t> rgb;
  const void* pixels = image.rgba.data();
  if (opaque) {
    png.format = PNG_FORMAT_RGB;
    rgb.resize(static_cast<std::size_t>(image.width) * image.height * 3);
    for (std::size_t p = 0, q = 0; p < image.rgba.size(); p += 4, q += 3) std::memcpy(&rgb[q], &image.rgba[p], 3);
    pixels = rgb.data();
  }
  // Ask for the size first, then encode into a buffer of that size.
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&png, nullptr, &size, 0, pixels, 0, nullptr))
    throw Error("", "PNG", std::string("cannot encode the image: ") + png.message);
  std::string out(size, '\0');
  if (!png_image_write_to_memory(&png, out.data(), &size, 0, pixels, 0, nullptr))
    throw Error("", "PNG", std::string("cannot encode the image: ") + png.message);
  out.resize(size);
  png_image_free(&png);
  return out;
}

void write_png(const Image& image, const std::filesystem::path& path) {
  write_file_atomic(path, encode_png(image));
}

Image decode_png(std::string_view bytes, const std::string& name, std::uint64_t max_pixels) {
  static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() < 8 || std::memcmp(bytes.data(), signature, 8) != 0)
    throw Error(name, "", "not a PNG file (the PNG signature is missing)");
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&png, bytes.data(), bytes.size()))
    throw Error(name, "", std::string("unreadable PNG: ") + png.message);
  const std::uint64_t pixels = std::uint64_t{png.width} * png.height;
  if (pixels > max_pixels || png.width > 0x7FFFFFFFu || png.height > 0x7FFFFFFFu) {
    png_image_free(&png);
    throw Error(name, "", std::to_string(png.width) + " x " + std::to_string(png.height) + " pixels is more than the " +
                              std::to_string(max_pixels) + " pixels vgd reads (--max-pixels)");
  }
  // Whatever is stored (grey, palette, 16-bit, alpha or not) comes out as 8-bit RGBA.
  png.format = PNG_FORMAT_RGBA;
  Image image(static_cast<int>(png.width), static_cast<int>(png.height));
  if (!png_image_finish_read(&png, nullptr, image.rgba.data(), 0, nullptr)) {
    const std::string message = png.message;
    png_image_free(&png);
    throw Error(name, "", "unreadable PNG: " + message);
  }
  return image;
}

Image read_png(const std::filesystem::path& path, std::uint64_t max_pixels) {
  return decode_png(read_file(path), path.string(), max_pixels);
}

}  // namespace vgd::render
