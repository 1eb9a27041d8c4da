// The image library: every use of OpenImageIO (reading images and textures,
// the texture cache's TextureSystem, writing EXR, PNG and JPEG) goes through
// this interface, implemented by the module pt_oiio.so (src/imagelib/oiio/),
// which is opened with dlopen the first time an image is read or written.
//
// Why: Debian's libOpenImageIO pulls in about 260 shared libraries (OpenCV,
// FFmpeg, DCMTK, GDCM, OpenVDB, ...), all bound at load time, which cost every
// run of the executable ~0.37 CPU-s before main() (docs/bench/startup.md).
// Neither the executable nor pt_io / pt_render link OpenImageIO: `--help`,
// `--version`, usage errors, bad scenes and pre-flight refusals never load it,
// and neither does a render that reads no image and writes only PPM.
//
// Where the module is looked for (first that exists, docs/cli.md "Image module"):
//   $PT_OIIO_MODULE, if set (then nothing else is tried);
//   pt_oiio.so beside the running executable (/proc/self/exe);
//   the build tree's pt_oiio.so (compiled in: tests and tools run from there).
//
// Both sides are compiled from this header in one build; the module states the
// interface it implements (kImageLibraryAbi, PT_VERSION and the compiler), and
// a module of another build is refused. Bump kImageLibraryAbi with any change
// to the classes below.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "io/exr_settings.h"
#include "io/image_metadata.h"
#include "io/layered_image.h"

namespace pt {

inline constexpr int kImageLibraryAbi = 5;

// What an image file's header says.
struct ImageHeader {
  int width = 0, height = 0, depth = 1;
  int nchannels = 0;
  int alpha_channel = -1;      // -1: none
  bool srgb_encoded = false;   // integer values not declared linear (PNG, JPEG, ...); float files are linear
};

// An image opened for reading (subimage 0, MIP level 0).
class ImageReader {
 public:
  virtual ~ImageReader() = default;
  virtual const ImageHeader& header() const = 0;
  // The first `channels` channels of every pixel as float, interleaved, row 0
  // at the top (width * height * channels values). Integer files give
  // code / max code.
  virtual bool read(int channels, float* out, std::string& error) = 0;
};

// An 8-bit display image to encode as PNG or JPEG.
struct DisplayImageFile {
  std::string format;  // "png" or "jpeg"
  int width = 0, height = 0;
  int channels = 3;  // 3 RGB, 4 RGBA (straight alpha)
  const unsigned char* pixels = nullptr;  // width * height * channels codes, row 0 at the top
  bool srgb = false;  // declare the sRGB colour space
  std::vector<std::pair<std::string, std::string>> text;  // text attributes (PNG tEXt)
  std::string description;                               // ImageDescription (JPEG: its comment)
};

// How the texture system filters a lookup and what it reads outside [0, 1].
enum class LookupFilter { Point, Bilinear, Trilinear, Anisotropic };
enum class LookupWrap { Repeat, Clamp, Black, Mirror };
struct LookupOptions {
  LookupFilter filter = LookupFilter::Anisotropic;
  LookupWrap wrap = LookupWrap::Repeat;
  int first_channel = 0;
  bool one_level = false;  // the coarsest MIP level only (a probe that reads every texel of an untiled image)
};

// OpenImageIO's ImageCache + TextureSystem, private to one owner (no shared
// cache). lookup() is thread-safe.
class TextureSystem {
 public:
  virtual ~TextureSystem() = default;
  // A handle for `file`; with `srgb_decode` the file's colour channels are
  // decoded from sRGB before the cache makes MIP levels (the name then is the
  // file's followed by kSrgbDecodedSuffix). nullptr with `error` on failure.
  virtual void* handle(const std::string& file, bool srgb_decode, std::string& error) = 0;
  virtual bool lookup(void* handle, const LookupOptions& options, float s, float t, float dsdx, float dtdx,
                      float dsdy, float dtdy, int n, float* out) const = 0;
  virtual std::string error() const = 0;  // the last error of this thread's lookups
  virtual std::string statistics(int level) const = 0;
};

inline constexpr const char* kSrgbDecodedSuffix = "#pt-srgb-decoded";

// An EXR file of one part written band by band, top to bottom, while the
// bands are made (the streamed merge: app/shard_band_merge.cpp). Opened with
// the image's layout (a LayeredImage's frame, window and layers' names,
// channels and types; no values), it writes the same bytes as write_exr of
// the whole image would (whatever the bands' heights). An uncompressed file
// is written without the module (io/exr_uncompressed.h, the same bytes).
class ExrBandWriter {
 public:
  virtual ~ExrBandWriter() = default;
  // The bytes of one packed row: every channel of a pixel in its file type
  // (half or float), interleaved, as the file stores them (io/exr_pack.h,
  // packed_layout of the layout's layers).
  virtual std::size_t row_bytes() const = 0;
  // Writes packed rows [y0, y1) (frame coordinates); each call's rows follow
  // the last call's. False with `error`.
  virtual bool write(int y0, int y1, const unsigned char* packed, std::string& error) = 0;
  // Writes rows [y0, y1) as the file stores them, when it stores them
  // uncompressed (io/exr_uncompressed.h, uncompressed_exr_lines: each row's
  // lines, after its y and byte count, which this sets); false with `error`
  // from writers of other files. Each call's rows follow the last call's.
  virtual bool write_lines(int y0, int y1, unsigned char* rows, std::string& error) {
    (void)y0, (void)y1, (void)rows;
    error = "this EXR writer takes packed rows, not lines";
    return false;
  }
  // Finishes the file (after every row). False with `error`.
  virtual bool close(std::string& error) = 0;
};

class ImageLibrary {
 public:
  virtual ~ImageLibrary() = default;
  virtual std::string version() const = 0;  // OpenImageIO's, e.g. "2.4.7"
  // `unassociated_alpha`: colour as stored, not multiplied by alpha.
  virtual std::unique_ptr<ImageReader> open(const std::string& path, bool unassociated_alpha,
                                            std::string& error) const = 0;
  // An image held in memory (kept alive by the caller while the reader is);
  // `format` is its kind as a file extension without the dot ("png").
  virtual std::unique_ptr<ImageReader> open_memory(const unsigned char* bytes, std::size_t size,
                                                   const std::string& format, std::string& error) const = 0;
  // Encodes `image` in memory (the caller writes the bytes: io/atomic_file.h).
  virtual bool encode(const DisplayImageFile& image, std::vector<unsigned char>& out, std::string& error) const = 0;
  // Writes `image` to `path` as OpenEXR (io/image_io.h, write_layered_image).
  virtual bool write_exr(const std::string& path, const LayeredImage& image, const ImageMetadata& metadata,
                         const ExrSettings& exr, std::string& error) const = 0;
  // Opens `path` for an EXR of `layout` (one part: exr.multipart is not
  // taken) written band by band. nullptr with `error` on failure.
  virtual std::unique_ptr<ExrBandWriter> open_exr(const std::string& path, const LayeredImage& layout,
                                                  const ImageMetadata& metadata, const ExrSettings& exr,
                                                  std::string& error) const = 0;
  virtual std::unique_ptr<TextureSystem> texture_system(uint64_t max_bytes) const = 0;
};

// The library, the module loaded on the first call (thread-safe; later calls
// return the same answer). nullptr and `error` naming the module's path and
// why if it cannot be loaded.
const ImageLibrary* image_library(std::string& error);
// The library if an earlier call loaded it, else nullptr (loads nothing).
const ImageLibrary* loaded_image_library();
// Where image_library() loads (or would load) the module from: the first
// candidate that exists, else the first candidate; `origin` says why there.
std::string image_module_path(std::string* origin = nullptr);
// The identity a module must report (its pt_image_library_abi()): both sides
// compute it from their own compilation.
inline std::string image_library_abi() {
  return "pt-image-library/" + std::to_string(kImageLibraryAbi) + " pathtracer " PT_VERSION " " __VERSION__;
}

}  // namespace pt

// The module's two entry points (C linkage, found with dlsym).
extern "C" {
const char* pt_image_library_abi();
const pt::ImageLibrary* pt_image_library();
}
