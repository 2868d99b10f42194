#include "png_codec.hpp"

#include "canvas.hpp"

#include <png.h>

#include <cstring>
#include <new>
#include <vector>

namespace swath::render::detail {
namespace {

// libpng reports errors by longjmp: the functions that call it hold only plain pointers between
// setjmp and the end, and the message is copied out before the jump.
struct ErrorText {
  char text[200] = "";
};

void on_error(png_structp png, png_const_charp message) {
  auto* error = static_cast<ErrorText*>(png_get_error_ptr(png));
  std::strncpy(error->text, message, sizeof error->text - 1);
  png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}

// No C++ exception may cross libpng's C frames: an allocation failure becomes a libpng error.
void write_to_string(png_structp png, png_bytep data, png_size_t length) {
  bool appended = true;
  try {
    static_cast<std::string*>(png_get_io_ptr(png))
        ->append(reinterpret_cast<const char*>(data), length);
  } catch (const std::bad_alloc&) {
    appended = false;
  }
  if (!appended) png_error(png, "out of memory");  // outside the handler: no jump out of it
}

struct Reader {
  const std::string* bytes;
  std::size_t at = 0;
};

void read_from_string(png_structp png, png_bytep data, png_size_t length) {
  auto* reader = static_cast<Reader*>(png_get_io_ptr(png));
  if (reader->at + length > reader->bytes->size()) png_error(png, "the PNG data ends early");
  std::memcpy(data, reader->bytes->data() + reader->at, length);
  reader->at += length;
}

// Returns false with `error` set; `rows` point into the image, `out` receives the bytes.
bool encode(const Image& image, png_bytep* rows, std::string* out, ErrorText* error) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, error, on_error, on_warning);
  if (png == nullptr) return false;
  png_infop info = png_create_info_struct(png);
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, out, write_to_string, nullptr);
  png_set_compression_level(png, 6);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_ALL_FILTERS);
  png_set_IHDR(png, info, image.width, image.height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_rows(png, info, rows);
  png_write_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

// Reads the header into width/height, then (rows != nullptr) the pixels.
bool decode(Reader* reader, Image* image, std::vector<png_bytep>* rows, ErrorText* error) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, error, on_error, on_warning);
  if (png == nullptr) return false;
  png_infop info = png_create_info_struct(png);
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_set_read_fn(png, reader, read_from_string);
  // Pixels a side, as many as draw() makes: no giant buffer from a bad header.
  png_set_user_limits(png, kMaxSide_px, kMaxSide_px);
  png_read_info(png, info);
  png_set_expand(png);  // palette to RGB, grey to 8 bits, tRNS to alpha
  png_set_strip_16(png);
  png_set_strip_alpha(png);
  png_set_gray_to_rgb(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  image->width = static_cast<int>(png_get_image_width(png, info));
  image->height = static_cast<int>(png_get_image_height(png, info));
  if (png_get_rowbytes(png, info) != 3 * static_cast<std::size_t>(image->width))
    png_error(png, "unexpected row size");
  bool allocated = true;
  try {
    image->rgb.resize(3 * static_cast<std::size_t>(image->width) * image->height);
    rows->resize(image->height);
  } catch (const std::bad_alloc&) {
    allocated = false;
  }
  if (!allocated) png_error(png, "out of memory");
  for (int y = 0; y < image->height; ++y)
    (*rows)[y] = image->rgb.data() + 3 * static_cast<std::size_t>(y) * image->width;
  png_read_image(png, rows->data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

}  // namespace

std::string png_encode(const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != 3 * static_cast<std::size_t>(image.width) * image.height)
    throw RenderError("cannot encode an empty or inconsistent image as PNG");
  std::vector<png_bytep> rows(image.height);
  for (int y = 0; y < image.height; ++y)
    rows[y] =
        const_cast<png_bytep>(image.rgb.data()) + 3 * static_cast<std::size_t>(y) * image.width;
  std::string out;
  ErrorText error;
  if (!encode(image, rows.data(), &out, &error))
    throw RenderError(std::string("cannot encode the PNG (") + error.text + ")");
  return out;
}

Image png_decode(const std::string& png) {
  if (png.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(png.data()), 0, 8) != 0)
    throw RenderError("not a PNG image");
  Reader reader{&png};
  Image image;
  std::vector<png_bytep> rows;
  ErrorText error;
  if (!decode(&reader, &image, &rows, &error))
    throw RenderError(std::string("not a readable PNG image (") + error.text + ")");
  return image;
}

}  // namespace swath::render::detail
