#include "sim/io/image_io.hpp"

#include <png.h>
#include <sys/stat.h>
// libjpeg's header needs size_t and FILE declared first.
#include <csetjmp>
#include <cstddef>
#include <cstdio>

#include <jpeglib.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>

namespace petra::io {

namespace {

using FilePtr = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

FilePtr open_file(const std::string& path, const char* mode) {
  return FilePtr(std::fopen(path.c_str(), mode), &std::fclose);
}

Error file_error(const std::string& path, const char* what) {
  return Error::make(Errc::io_error, "%s: %s", path.c_str(), what);
}

Error format_error(const std::string& path, const char* what) {
  return Error::make(Errc::parse_error, "%s: %s", path.c_str(), what);
}

// Raw decoded image: channels 1..4, 8-bit samples.
struct Decoded {
  int width = 0, height = 0, channels = 0;
  std::vector<std::uint8_t> samples;
};

// --- PNM (PGM/PPM) -----------------------------------------------------------

bool pnm_token(const std::string& data, std::size_t& pos, std::string& out) {
  out.clear();
  while (pos < data.size()) {
    const char c = data[pos];
    if (c == '#') {
      while (pos < data.size() && data[pos] != '\n') ++pos;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++pos;
    } else {
      break;
    }
  }
  while (pos < data.size() && !std::isspace(static_cast<unsigned char>(data[pos])))
    out += data[pos++];
  return !out.empty();
}

bool parse_uint(const std::string& s, long max, long& v) {
  if (s.empty() || s.size() > 9) return false;
  for (char c : s)
    if (c < '0' || c > '9') return false;
  v = std::stol(s);
  return v <= max;
}

bool parse_positive(const std::string& s, long max, long& v) {
  return parse_uint(s, max, v) && v > 0;
}

Result<Decoded> decode_pnm(const std::string& path, const std::string& data) {
  std::size_t pos = 0;
  std::string magic, tok;
  if (!pnm_token(data, pos, magic)) return format_error(path, "empty file");
  const bool ascii = magic == "P2" || magic == "P3";
  const bool gray = magic == "P2" || magic == "P5";
  if (magic != "P2" && magic != "P3" && magic != "P5" && magic != "P6")
    return format_error(path, "not a PGM/PPM (magic)");
  long w = 0, h = 0, maxval = 0;
  if (!pnm_token(data, pos, tok) || !parse_positive(tok, 1 << 15, w))
    return format_error(path, "bad width");
  if (!pnm_token(data, pos, tok) || !parse_positive(tok, 1 << 15, h))
    return format_error(path, "bad height");
  if (!pnm_token(data, pos, tok) || !parse_positive(tok, 65535, maxval))
    return format_error(path, "bad maxval");
  ++pos;  // the single whitespace after maxval
  Decoded d;
  d.width = static_cast<int>(w);
  d.height = static_cast<int>(h);
  d.channels = gray ? 1 : 3;
  const std::size_t n = static_cast<std::size_t>(w) * h * d.channels;
  d.samples.resize(n);
  auto scale = [&](long v) {
    return static_cast<std::uint8_t>(maxval == 255 ? v : (v * 255 + maxval / 2) / maxval);
  };
  if (ascii) {
    for (std::size_t i = 0; i < n; ++i) {
      long v = 0;
      if (!pnm_token(data, pos, tok) || !parse_uint(tok, 65535, v))
        return format_error(path, "truncated or bad sample");
      if (v > maxval) return format_error(path, "sample above maxval");
      d.samples[i] = scale(v);
    }
  } else {
    const std::size_t bytes = maxval > 255 ? 2 : 1;
    if (data.size() < pos || data.size() - pos < n * bytes)
      return format_error(path, "truncated pixel data");
    for (std::size_t i = 0; i < n; ++i) {
      long v = bytes == 1 ? static_cast<unsigned char>(data[pos + i])
                          : (static_cast<unsigned char>(data[pos + 2 * i]) << 8) |
                                static_cast<unsigned char>(data[pos + 2 * i + 1]);
      if (v > maxval) return format_error(path, "sample above maxval");
      d.samples[i] = scale(v);
    }
  }
  return d;
}

// --- PNG -----------------------------------------------------------------------

Result<Decoded> decode_png(const std::string& path) {
  png_image img;
  std::memset(&img, 0, sizeof img);
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&img, path.c_str()))
    return format_error(path, img.message[0] ? img.message : "unreadable PNG");
  Decoded d;
  const bool colour = (img.format & PNG_FORMAT_FLAG_COLOR) != 0;
  img.format = colour ? PNG_FORMAT_RGB : PNG_FORMAT_GRAY;  // alpha dropped, 16-bit reduced
  d.width = static_cast<int>(img.width);
  d.height = static_cast<int>(img.height);
  d.channels = colour ? 3 : 1;
  if (img.width == 0 || img.height == 0 || img.width > (1u << 15) || img.height > (1u << 15)) {
    png_image_free(&img);
    return format_error(path, "PNG size out of range");
  }
  d.samples.resize(PNG_IMAGE_SIZE(img));
  if (!png_image_finish_read(&img, nullptr, d.samples.data(), 0, nullptr)) {
    std::string msg = img.message;
    png_image_free(&img);
    return format_error(path, msg.empty() ? "corrupt PNG" : msg.c_str());
  }
  return d;
}

// --- JPEG ----------------------------------------------------------------------

// libjpeg reports fatal errors through error_exit, which must not return: it
// jumps back to decode_jpeg_into. Only trivially destructible locals live
// between setjmp and longjmp, so no destructor is skipped.
struct JpegErrorManager {
  jpeg_error_mgr base;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

void jpeg_error_exit(j_common_ptr cinfo) {
  auto* err = reinterpret_cast<JpegErrorManager*>(cinfo->err);  // NOLINT: libjpeg's C idiom
  (*cinfo->err->format_message)(cinfo, err->message);
  std::longjmp(err->jump, 1);
}

void jpeg_silent(j_common_ptr, int) {}  // warnings (e.g. extraneous bytes) are not errors

// Decodes into d; returns false with err.message set on failure. Gray output
// is libjpeg's luminance channel, as OpenCV's imread(..., IMREAD_GRAYSCALE).
// d lives in the caller's frame, so its destructor is never skipped.
bool decode_jpeg_into(const std::string& data, bool gray, Decoded& d, JpegErrorManager& err) {
  jpeg_decompress_struct cinfo;
  cinfo.err = jpeg_std_error(&err.base);
  err.base.error_exit = jpeg_error_exit;
  err.base.emit_message = jpeg_silent;
  err.message[0] = '\0';
  if (setjmp(err.jump)) {
    jpeg_destroy_decompress(&cinfo);
    return false;
  }
  jpeg_create_decompress(&cinfo);
  jpeg_mem_src(&cinfo, reinterpret_cast<const unsigned char*>(data.data()),  // NOLINT
               static_cast<unsigned long>(data.size()));
  jpeg_read_header(&cinfo, TRUE);
  if (cinfo.image_width == 0 || cinfo.image_height == 0 || cinfo.image_width > (1u << 15) ||
      cinfo.image_height > (1u << 15)) {
    std::snprintf(err.message, sizeof err.message, "JPEG size out of range");
    jpeg_destroy_decompress(&cinfo);
    return false;
  }
  cinfo.out_color_space = gray ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_start_decompress(&cinfo);
  d.width = static_cast<int>(cinfo.output_width);
  d.height = static_cast<int>(cinfo.output_height);
  d.channels = cinfo.output_components;
  const std::size_t row_bytes = static_cast<std::size_t>(d.width) * d.channels;
  d.samples.resize(row_bytes * d.height);
  while (cinfo.output_scanline < cinfo.output_height) {
    JSAMPROW row = d.samples.data() + static_cast<std::size_t>(cinfo.output_scanline) * row_bytes;
    jpeg_read_scanlines(&cinfo, &row, 1);
  }
  jpeg_finish_decompress(&cinfo);
  jpeg_destroy_decompress(&cinfo);
  return true;
}

Result<Decoded> decode_jpeg(const std::string& path, const std::string& data, bool gray) {
  Decoded d;
  JpegErrorManager err;
  if (!decode_jpeg_into(data, gray, d, err))
    return format_error(path, err.message[0] ? err.message : "corrupt JPEG");
  return d;
}

Result<Decoded> decode_any(const std::string& path, bool gray) {
  auto data = read_text_file(path);
  if (!data) return data.error();
  if (data->size() >= 8 && std::memcmp(data->data(), "\x89PNG\r\n\x1a\n", 8) == 0)
    return decode_png(path);
  if (data->size() >= 3 && std::memcmp(data->data(), "\xff\xd8\xff", 3) == 0)
    return decode_jpeg(path, *data, gray);
  if (data->size() >= 2 && (*data)[0] == 'P') return decode_pnm(path, *data);
  return format_error(path, "unknown image format (expected PGM, PPM, PNG or JPEG)");
}

Status write_png_raw(const std::string& path, int w, int h, bool colour, const std::uint8_t* data,
                     std::ptrdiff_t row_stride) {
  png_image img;
  std::memset(&img, 0, sizeof img);
  img.version = PNG_IMAGE_VERSION;
  img.width = static_cast<png_uint_32>(w);
  img.height = static_cast<png_uint_32>(h);
  img.format = colour ? PNG_FORMAT_RGB : PNG_FORMAT_GRAY;
  auto f = open_file(path, "wb");
  if (!f) return file_error(path, std::strerror(errno));
  if (!png_image_write_to_stdio(&img, f.get(), 0, data, static_cast<png_int_32>(row_stride),
                                nullptr))
    return file_error(path, img.message[0] ? img.message : "cannot write PNG");
  if (std::fflush(f.get()) != 0) return file_error(path, std::strerror(errno));
  return {};
}

}  // namespace

Result<GrayImage> read_gray_image(const std::string& path) {
  auto d = decode_any(path, true);
  if (!d) return d.error();
  GrayImage g(d->width, d->height);
  const std::size_t n = g.pixels.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (d->channels == 1) {
      g.pixels[i] = d->samples[i];
    } else {
      const std::uint8_t* p = &d->samples[i * 3];
      g.pixels[i] = rgb_to_gray(p[0], p[1], p[2]);
    }
  }
  return g;
}

Result<RgbImage> read_rgb_image(const std::string& path) {
  auto d = decode_any(path, false);
  if (!d) return d.error();
  RgbImage out(d->width, d->height);
  const std::size_t n = static_cast<std::size_t>(d->width) * d->height;
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      out.rgb[i * 3 + c] = d->channels == 1 ? d->samples[i] : d->samples[i * 3 + c];
  return out;
}

Status write_pgm(const std::string& path, ConstGray8View image) {
  auto f = open_file(path, "wb");
  if (!f) return file_error(path, std::strerror(errno));
  std::fprintf(f.get(), "P5\n%d %d\n255\n", image.width(), image.height());
  for (int y = 0; y < image.height(); ++y)
    if (std::fwrite(image.row(y), 1, static_cast<std::size_t>(image.width()), f.get()) !=
        static_cast<std::size_t>(image.width()))
      return file_error(path, std::strerror(errno));
  if (std::fflush(f.get()) != 0) return file_error(path, std::strerror(errno));
  return {};
}

Status write_png(const std::string& path, ConstGray8View image) {
  return write_png_raw(path, image.width(), image.height(), false, image.data(), image.stride());
}

Status write_png(const std::string& path, const RgbImage& image) {
  return write_png_raw(path, image.width, image.height, true, image.rgb.data(), image.width * 3);
}

Result<FloatImage> read_pfm(const std::string& path) {
  auto data = read_text_file(path);
  if (!data) return data.error();
  std::size_t pos = 0;
  std::string magic, tok;
  if (!pnm_token(*data, pos, magic) || magic != "Pf")
    return format_error(path, "not a gray PFM (Pf)");
  long w = 0, h = 0;
  if (!pnm_token(*data, pos, tok) || !parse_positive(tok, 1 << 15, w))
    return format_error(path, "bad width");
  if (!pnm_token(*data, pos, tok) || !parse_positive(tok, 1 << 15, h))
    return format_error(path, "bad height");
  if (!pnm_token(*data, pos, tok)) return format_error(path, "missing scale");
  double scale = 0;
  try {
    scale = std::stod(tok);
  } catch (...) {
    return format_error(path, "bad scale");
  }
  if (scale == 0 || !std::isfinite(scale)) return format_error(path, "bad scale");
  ++pos;
  const bool little = scale < 0;
  const std::size_t n = static_cast<std::size_t>(w) * h;
  if (data->size() < pos || data->size() - pos < n * 4)
    return format_error(path, "truncated pixel data");
  FloatImage img(static_cast<int>(w), static_cast<int>(h));
  for (long y = 0; y < h; ++y)
    for (long x = 0; x < w; ++x) {
      const unsigned char* b = reinterpret_cast<const unsigned char*>(data->data()) + pos +
                               (static_cast<std::size_t>(h - 1 - y) * w + x) * 4;
      std::uint32_t u =
          little ? (b[0] | b[1] << 8 | b[2] << 16 | static_cast<std::uint32_t>(b[3]) << 24)
                 : (b[3] | b[2] << 8 | b[1] << 16 | static_cast<std::uint32_t>(b[0]) << 24);
      float v;
      std::memcpy(&v, &u, 4);
      img.data[static_cast<std::size_t>(y) * w + x] = v;
    }
  return img;
}

Status write_pfm(const std::string& path, ImageView<const float> image) {
  auto f = open_file(path, "wb");
  if (!f) return file_error(path, std::strerror(errno));
  std::fprintf(f.get(), "Pf\n%d %d\n-1\n", image.width(), image.height());
  std::vector<unsigned char> row(static_cast<std::size_t>(image.width()) * 4);
  for (int y = image.height() - 1; y >= 0; --y) {
    for (int x = 0; x < image.width(); ++x) {
      std::uint32_t u;
      std::memcpy(&u, &image(x, y), 4);
      for (int k = 0; k < 4; ++k)
        row[static_cast<std::size_t>(x) * 4 + k] = static_cast<unsigned char>(u >> (8 * k));
    }
    if (std::fwrite(row.data(), 1, row.size(), f.get()) != row.size())
      return file_error(path, std::strerror(errno));
  }
  if (std::fflush(f.get()) != 0) return file_error(path, std::strerror(errno));
  return {};
}

Result<std::string> read_text_file(const std::string& path, std::size_t max_bytes) {
  auto f = open_file(path, "rb");
  if (!f) return file_error(path, std::strerror(errno));
  struct stat st {};
  if (::fstat(::fileno(f.get()), &st) != 0) return file_error(path, std::strerror(errno));
  if (S_ISDIR(st.st_mode)) return file_error(path, "is a directory, not a file");
  std::string s;
  char chunk[65536];
  for (;;) {  // also reads pipes and /proc files, whose size is unknown
    const std::size_t n = std::fread(chunk, 1, sizeof chunk, f.get());
    s.append(chunk, n);
    if (s.size() > max_bytes) {
      char why[64];
      std::snprintf(why, sizeof why, "larger than %zu bytes", max_bytes);
      return file_error(path, why);
    }
    if (n < sizeof chunk) break;
  }
  if (std::ferror(f.get())) return file_error(path, std::strerror(errno));
  return s;
}

Status write_text_file(const std::string& path, std::string_view text) {
  return write_binary_file(path, text.data(), text.size());
}

Status write_binary_file(const std::string& path, const void* data, std::size_t bytes) {
  auto f = open_file(path, "wb");
  if (!f) return file_error(path, std::strerror(errno));
  if (bytes > 0 && std::fwrite(data, 1, bytes, f.get()) != bytes)
    return file_error(path, std::strerror(errno));
  if (std::fflush(f.get()) != 0) return file_error(path, std::strerror(errno));
  return {};
}

}  // namespace petra::io
