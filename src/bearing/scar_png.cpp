// Imported scars from a 16-bit grayscale PNG (issue #27): libpng's simplified reading API would
// convert any format silently, so the low-level API reads the header first and accepts only bit
// depth 16, colour type gray (no palette, no alpha, no conversion). Optional: without libpng
// (INTERFERE_WITH_PNG undefined) the reader answers that the build has none.
#include <cmath>
#include <cstdio>
#include <memory>

#include "scar_number.h"
#include "interfere/bearing/scar_import.h"

#ifdef INTERFERE_WITH_PNG
#include <png.h>

#include <csetjmp>
#endif

namespace interfere::bearing {
using detail::scar_number;

bool scar_png_supported() {
#ifdef INTERFERE_WITH_PNG
  return true;
#else
  return false;
#endif
}

Expected<HeightMap> read_scar_png(const std::string& path, double scale, double offset,
                                  const MapPlacement& where) {
  if (!std::isfinite(scale))
    return Error{.file = path, .reason = "the PNG height scale must be finite, got " + scar_number(scale)};
  if (!std::isfinite(offset))
    return Error{.file = path,
                 .reason = "the PNG height offset must be finite, got " + scar_number(offset)};
  if (!(std::isfinite(where.angle_min_deg) && std::isfinite(where.angle_max_deg) &&
        where.angle_max_deg > where.angle_min_deg &&
        where.angle_max_deg - where.angle_min_deg < 360))
    return Error{
        .file = path,
        .reason = "the map's angles must satisfy angle_min < angle_max < angle_min + 360, got " +
                  scar_number(where.angle_min_deg) + " .. " + scar_number(where.angle_max_deg)};
  if (!(std::isfinite(where.z_min) && std::isfinite(where.z_max) && where.z_max > where.z_min))
    return Error{.file = path,
                 .reason = "the map's z range must satisfy z_min < z_max, got " + scar_number(where.z_min) +
                           " .. " + scar_number(where.z_max)};
#ifndef INTERFERE_WITH_PNG
  (void)scale, (void)offset;
  return Error{
      .file = path,
      .reason = "this build has no PNG reader (libpng was not found when it was configured)"};
#else
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) return Error{.file = path, .reason = "cannot open the scar height map"};
  unsigned char sig[8];
  if (std::fread(sig, 1, 8, f.get()) != 8 || png_sig_cmp(sig, 0, 8) != 0)
    return Error{.file = path, .byte = 0, .reason = "not a PNG file (bad signature)"};
  struct Ctx {
    std::string message;
  } ctx;
  png_structp png = png_create_read_struct(
      PNG_LIBPNG_VER_STRING, &ctx,
      [](png_structp p, png_const_charp msg) {
        static_cast<Ctx*>(png_get_error_ptr(p))->message = msg;
        png_longjmp(p, 1);
      },
      [](png_structp, png_const_charp) {});
  if (!png) return Error{.file = path, .reason = "libpng: cannot create a reader"};
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    return Error{.file = path, .reason = "libpng: cannot create a reader"};
  }
  HeightMap map;
  map.source = path;
  map.from_png = true;
  std::vector<png_byte> data;
  std::vector<png_bytep> rows;
  png_uint_32 w = 0, h = 0;
  int depth = 0, color = 0;
  std::string problem;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return Error{.file = path,
                 .reason = "invalid PNG: " +
                           (ctx.message.empty() ? std::string("libpng error") : ctx.message)};
  }
  png_init_io(png, f.get());
  png_set_sig_bytes(png, 8);
  png_read_info(png, info);
  w = png_get_image_width(png, info), h = png_get_image_height(png, info);
  depth = png_get_bit_depth(png, info), color = png_get_color_type(png, info);
  if (color != PNG_COLOR_TYPE_GRAY || depth != 16) {
    const char* kind = color == PNG_COLOR_TYPE_GRAY         ? "gray"
                       : color == PNG_COLOR_TYPE_GRAY_ALPHA ? "gray with alpha"
                       : color == PNG_COLOR_TYPE_RGB        ? "RGB"
                       : color == PNG_COLOR_TYPE_RGB_ALPHA  ? "RGBA"
                       : color == PNG_COLOR_TYPE_PALETTE    ? "palette"
                                                            : "unknown";
    problem = std::string("a scar height map must be a 16-bit grayscale PNG, this one is ") + kind +
              ", " + std::to_string(depth) + "-bit";
  } else if (w < 2 || h < 2) {
    problem = "a height map needs at least 2 x 2 pixels, got " + std::to_string(w) + " x " +
              std::to_string(h);
  } else if (static_cast<double>(w) * h > 1e8) {
    problem = "the image is too large (" + std::to_string(w) + " x " + std::to_string(h) +
              " > 10^8 pixels)";
  }
  if (!problem.empty()) {
    png_destroy_read_struct(&png, &info, nullptr);
    return Error{.file = path, .reason = problem};
  }
  if (png_get_interlace_type(png, info) != PNG_INTERLACE_NONE) png_set_interlace_handling(png);
  png_read_update_info(png, info);
  const std::size_t stride = png_get_rowbytes(png, info);
  data.resize(stride * h);
  rows.resize(h);
  for (png_uint_32 y = 0; y < h; ++y) rows[y] = data.data() + stride * y;
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  // rows of the map bottom-up (z increasing): map row r is pixel row h - 1 - r
  map.angle_deg.resize(w);
  map.z.resize(h);
  for (png_uint_32 x = 0; x < w; ++x)
    map.angle_deg[x] = x + 1 == w ? where.angle_max_deg
                                  : where.angle_min_deg +
                                        (where.angle_max_deg - where.angle_min_deg) * x / (w - 1);
  for (png_uint_32 r = 0; r < h; ++r)
    map.z[r] = r + 1 == h ? where.z_max : where.z_min + (where.z_max - where.z_min) * r / (h - 1);
  map.height.resize(static_cast<std::size_t>(w) * h);
  for (png_uint_32 r = 0; r < h; ++r) {
    const png_byte* row = rows[h - 1 - r];
    for (png_uint_32 x = 0; x < w; ++x) {
      const unsigned v =
          (static_cast<unsigned>(row[2 * x]) << 8) | row[2 * x + 1];  // big-endian samples
      const double height = scale * v + offset;
      if (!std::isfinite(height))
        return Error{.file = path,
                     .reason = "pixel (" + std::to_string(x) + ", " + std::to_string(h - 1 - r) +
                               "): height " + scar_number(height) + " is not finite"};
      map.height[static_cast<std::size_t>(r) * w + x] = height;
    }
  }
  return map;
#endif
}

}  // namespace interfere::bearing
