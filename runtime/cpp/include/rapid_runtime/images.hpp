// Synthetic pictures for the simulated robot (the C++ twin of runtime/rapid_runtime/images.py):
// a landscape (sky, sun, ground with rocks, seen from a heading; a frame counter in the
// bottom-left corner) painted on a grid of 8x8-pixel blocks and encoded as the MIME type
// asks: PNG (deflate written here: literals and matches one pixel or one row back), baseline
// JPEG (one DC coefficient per block), BMP or PNM. No library beyond the standard one.
// A 1360x1024 JPEG is about 30 KB, a 640x480 PNG a few KB: well within
// ImageSensorSample.data (1 MiB).
#ifndef RAPID_RUNTIME_IMAGES_HPP
#define RAPID_RUNTIME_IMAGES_HPP

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace rapid_runtime {

class ImageError : public std::invalid_argument {
public:
    explicit ImageError(const std::string& why) : std::invalid_argument(why) {}
};

// Whether synthetic() paints this MIME type (png, jpeg, bmp, x-portable-graymap/pixmap).
bool can_paint(const std::string& mime);

// A picture of width x height pixels encoded as mime; grey for a mono sensor; heading (rad)
// pans the view, frame is shown in binary. ImageError for another MIME type or a size
// below one pixel or over 65535.
std::vector<std::uint8_t> synthetic_image(const std::string& mime, int width, int height, double heading = 0.0,
                                          std::uint32_t frame = 0, bool grey = false);

// What a picture's own header says (PNG, JPEG, BMP, PNM): false when none of them.
struct ImageInfo {
    std::string mime;
    int width = 0;
    int height = 0;
};
bool describe_image(const std::vector<std::uint8_t>& data, ImageInfo& info);

}  // namespace rapid_runtime

#endif
