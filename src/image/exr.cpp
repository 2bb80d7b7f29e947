// OpenEXR through the generic frame-buffer API, so that FLOAT channels are read and written
// without going through half precision.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <exception>

#include "image/exr_check.h"
#include "image/formats.h"

namespace tuneray::detail {

Image read_exr(const std::string& path) {
  check_exr_header(path);  // before OpenEXR allocates what a hostile header asks for
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const long long width = static_cast<long long>(window.max.x) - window.min.x + 1;
    const long long height = static_cast<long long>(window.max.y) - window.min.y + 1;
    check_dimensions(path, width, height);

    const Imf::ChannelList& channels = file.header().channels();
    const bool has_rgb =
        channels.findChannel("R") || channels.findChannel("G") || channels.findChannel("B");
    const bool has_luminance = channels.findChannel("Y") != nullptr;
    if (!has_rgb && !has_luminance) {
      throw ImageError(path + ": EXR file has no R, G, B or Y channel");
    }

    Image image(static_cast<int>(width), static_cast<int>(height));
    char* base = reinterpret_cast<char*>(image.data());
    const size_t x_stride = sizeof(Color), y_stride = sizeof(Color) * image.width();
    Imf::FrameBuffer frame;
    if (has_rgb) {
      const char* names[3] = {"R", "G", "B"};
      for (int k = 0; k < 3; ++k) {
        frame.insert(names[k], Imf::Slice::Make(Imf::FLOAT, base + k * sizeof(float), window,
                                                x_stride, y_stride));
      }
    } else {
      frame.insert("Y", Imf::Slice::Make(Imf::FLOAT, base, window, x_stride, y_stride));
    }
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    if (!has_rgb) {
      for (size_t i = 0; i < image.pixel_count(); ++i) image.data()[i] = Color(image.data()[i].x);
    }
    return image;
  } catch (const ImageError&) {
    throw;
  } catch (const std::exception& e) {
    throw ImageError(path + ": cannot read EXR: " + e.what());
  }
}

void write_exr(const std::string& path, const Image& image) {
  try {
    Imf::Header header(image.width(), image.height());
    header.compression() = Imf::ZIP_COMPRESSION;
    const char* names[3] = {"R", "G", "B"};
    for (const char* name : names) header.channels().insert(name, Imf::Channel(Imf::FLOAT));

    // OpenEXR's Slice wants a mutable pointer even for output; it only reads through it.
    char* base = const_cast<char*>(reinterpret_cast<const char*>(image.data()));
    const size_t x_stride = sizeof(Color), y_stride = sizeof(Color) * image.width();
    Imf::FrameBuffer frame;
    for (int k = 0; k < 3; ++k) {
      frame.insert(names[k], Imf::Slice(Imf::FLOAT, base + k * sizeof(float), x_stride, y_stride));
    }
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(image.height());
  } catch (const std::exception& e) {
    throw ImageError(path + ": cannot write EXR: " + e.what());
  }
}

}  // namespace tuneray::detail
